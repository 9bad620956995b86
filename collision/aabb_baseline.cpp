#include "collision/aabb_baseline.hpp"

#include "geometry/organ_mesh.hpp"

#include <algorithm>

namespace canopy {
namespace {
bool boxes_meet(const float* a, const float* b) {
  return a[0] <= b[3] && b[0] <= a[3] && a[1] <= b[4] && b[1] <= a[4] && a[2] <= b[5] && b[2] <= a[5];
}
}  // namespace

void AabbTree::build(const Stand& s, PrototypeLibrary& lib, const KindMask& collide, float clearance) {
  const std::size_t n = s.organ_count();
  box_.assign(n, {});
  ids_.clear();
  for (std::size_t i = 0; i < n; ++i)
    if (collide[static_cast<std::size_t>(s.organs[i].kind)]) ids_.push_back(static_cast<std::uint32_t>(i));
  make_meshes(s, lib);
#pragma omp parallel
  {
    OrganMesh mesh;
#pragma omp for schedule(dynamic, 256)
    for (std::size_t k = 0; k < ids_.size(); ++k) {
      const std::uint32_t id = ids_[k];
      organ_mesh(s, id, lib, mesh, true);
      const Vec3d off = s.offset(static_cast<std::size_t>(s.organs[id].plant));
      auto& b = box_[id];
      b = {1e30f, 1e30f, 1e30f, -1e30f, -1e30f, -1e30f};
      for (const Vec3f& v : mesh.positions) {
        const float p[3] = {static_cast<float>(off.x + v.x), static_cast<float>(off.y + v.y), v.z};
        for (int d = 0; d < 3; ++d) b[d] = min_f(b[d], p[d]), b[d + 3] = max_f(b[d + 3], p[d]);
      }
      for (int d = 0; d < 3; ++d) b[d] -= clearance + 1e-5f, b[d + 3] += clearance + 1e-5f;
    }
  }
  nodes_.clear();
  nodes_.reserve(2 * ids_.size() / 4 + 2);
  if (!ids_.empty()) build_node(0, static_cast<std::uint32_t>(ids_.size()));
}

std::int32_t AabbTree::build_node(std::uint32_t first, std::uint32_t count) {
  Node node;
  for (int d = 0; d < 3; ++d) node.lo[d] = 1e30f, node.hi[d] = -1e30f;
  for (std::uint32_t k = first; k < first + count; ++k)
    for (int d = 0; d < 3; ++d)
      node.lo[d] = min_f(node.lo[d], box_[ids_[k]][d]), node.hi[d] = max_f(node.hi[d], box_[ids_[k]][d + 3]);
  const auto index = static_cast<std::int32_t>(nodes_.size());
  node.first = first, node.count = count;
  nodes_.push_back(node);
  if (count <= 4) return index;
  int axis = 0;
  for (int d = 1; d < 3; ++d)
    if (node.hi[d] - node.lo[d] > node.hi[axis] - node.lo[axis]) axis = d;
  const std::uint32_t half = count / 2;
  std::nth_element(ids_.begin() + first, ids_.begin() + first + half, ids_.begin() + first + count,
                   [&](std::uint32_t a, std::uint32_t b) {
                     return box_[a][axis] + box_[a][axis + 3] < box_[b][axis] + box_[b][axis + 3];
                   });
  const std::int32_t l = build_node(first, half);
  const std::int32_t r = build_node(first + half, count - half);
  nodes_[static_cast<std::size_t>(index)].left = l;
  nodes_[static_cast<std::size_t>(index)].right = r;
  return index;
}

std::vector<Contact> AabbTree::overlapping_pairs(const Stand& s) const {
  std::vector<Contact> out;
  if (nodes_.empty()) return out;
#pragma omp parallel
  {
    std::vector<Contact> mine;
    std::vector<std::int32_t> stack;
#pragma omp for schedule(dynamic, 256)
    for (std::size_t k = 0; k < ids_.size(); ++k) {
      const std::uint32_t a = ids_[k];
      const float* ba = box_[a].data();
      stack.assign(1, 0);
      while (!stack.empty()) {
        const Node& nd = nodes_[static_cast<std::size_t>(stack.back())];
        stack.pop_back();
        if (ba[0] > nd.hi[0] || nd.lo[0] > ba[3] || ba[1] > nd.hi[1] || nd.lo[1] > ba[4] ||
            ba[2] > nd.hi[2] || nd.lo[2] > ba[5])
          continue;
        if (nd.left >= 0) {
          stack.push_back(nd.left);
          stack.push_back(nd.right);
          continue;
        }
        for (std::uint32_t j = nd.first; j < nd.first + nd.count; ++j) {
          const std::uint32_t b = ids_[j];
          if (b <= a || !boxes_meet(ba, box_[b].data())) continue;
          const auto ia = static_cast<std::int32_t>(a), ib = static_cast<std::int32_t>(b);
          if (adjacent(s.organs[a], ia, s.organs[b], ib)) continue;
          mine.push_back({ia, ib, s.organs[a].plant, s.organs[b].plant, -1, -1});
        }
      }
    }
#pragma omp critical
    out.insert(out.end(), mine.begin(), mine.end());
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace canopy
