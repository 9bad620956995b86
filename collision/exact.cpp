#include "collision/exact.hpp"

#include "collision/mbvt.hpp"
#include "geometry/triangle_test.hpp"

#include <algorithm>
#include <cassert>

namespace canopy {
namespace {

/// 10 µm: far above the float rounding of a plane test on plant-frame coordinates (about 1e-7 m).
constexpr float kPlaneSlack = 1e-5f;

/// The n-th index of 0..count-1 in the order start, start+1, start-1, start+2, ... (wrapping):
/// triangles of neighbouring indices lie side by side on a prototype mesh, so a search that
/// starts at the triangle that touched last meets its neighbours on both sides first.
std::size_t spiral(std::size_t start, std::size_t n, std::size_t count) {
  const std::size_t step = (n + 1) / 2;
  return n % 2 ? (start + step) % count : (start + count - step % count) % count;
}

}  // namespace

void organ_vertices(const Stand& s, const PrototypeMesh& mesh, std::int32_t organ, std::int32_t frame_plant,
                    std::vector<Vec3f>& out) {
  organ_vertices(s, mesh, s.transforms[static_cast<std::size_t>(organ)], s.organs[static_cast<std::size_t>(organ)].plant,
                 frame_plant, out);
}

void organ_vertices(const Stand& s, const PrototypeMesh& mesh, const Affine3f& m, std::int32_t plant, std::int32_t frame_plant,
                    std::vector<Vec3f>& out) {
  const Vec3f d = plant == frame_plant ? Vec3f{0, 0, 0} : plant_offset(s, frame_plant, plant);
  out.resize(mesh.positions.size());
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) out[i] = apply(m, mesh.positions[i]) + d;
}

bool organs_touch(const Stand& s, PrototypeLibrary& lib, std::int32_t a, std::int32_t b, float clearance, ExactScratch& x) {
  return organs_touch_at(s, lib, a, s.transforms[static_cast<std::size_t>(a)], b, s.transforms[static_cast<std::size_t>(b)],
                         clearance, x);
}

bool organs_touch_at(const Stand& s, PrototypeLibrary& lib, std::int32_t a, const Affine3f& pose_a, std::int32_t b,
                     const Affine3f& pose_b, float clearance, ExactScratch& x, Witness* witness) {
  assert(a < b);
  const OrganRecord& ra = s.organs[static_cast<std::size_t>(a)];
  const OrganRecord& rb = s.organs[static_cast<std::size_t>(b)];
  const PrototypeMesh& ma = lib.get(ra.prototype, ra.lod);
  const PrototypeMesh& mb = lib.get(rb.prototype, rb.lod);
  const std::size_t ta = ma.triangle_count(), tb = mb.triangle_count();
  const double c = clearance;
  const Vec3f d = rb.plant == ra.plant ? Vec3f{0, 0, 0} : plant_offset(s, ra.plant, rb.plant);
  // The witness pairs first, newest first, their six vertices made as organ_vertices makes them.
  for (int n = 0; witness && n < Witness::kSlots; ++n) {
    const int slot = (witness->latest - n + Witness::kSlots) % Witness::kSlots;
    const std::size_t wa = witness->tri_a[slot], wb = witness->tri_b[slot];
    if (wa >= ta || wb >= tb) continue;
    Vec3f p[3], q[3];
    for (int k = 0; k < 3; ++k) {
      p[k] = apply(pose_a, ma.positions[ma.indices[3 * wa + static_cast<std::size_t>(k)]]) + Vec3f{0, 0, 0};
      q[k] = apply(pose_b, mb.positions[mb.indices[3 * wb + static_cast<std::size_t>(k)]]) + d;
    }
    if (c > 0 ? triangles_within(p, q, c, true) : triangles_intersect(p, q)) return true;
  }
  organ_vertices(s, ma, pose_a, ra.plant, ra.plant, x.va);
  organ_vertices(s, mb, pose_b, rb.plant, ra.plant, x.vb);
  // Boxes of both organs' triangles; only triangles inside the other organ's (widened) box can
  // meet anything of it.
  const auto tri_box = [](const std::vector<Vec3f>& v, const std::vector<std::uint32_t>& idx, std::size_t t, float* bx) {
    const Vec3f p = v[idx[3 * t]], q = v[idx[3 * t + 1]], r = v[idx[3 * t + 2]];
    bx[0] = min_f(p.x, min_f(q.x, r.x)), bx[1] = min_f(p.y, min_f(q.y, r.y)), bx[2] = min_f(p.z, min_f(q.z, r.z));
    bx[3] = max_f(p.x, max_f(q.x, r.x)), bx[4] = max_f(p.y, max_f(q.y, r.y)), bx[5] = max_f(p.z, max_f(q.z, r.z));
  };
  const auto organ_box = [](const std::vector<Vec3f>& v, double* bx, double widen) {
    bx[0] = bx[1] = bx[2] = 1e300, bx[3] = bx[4] = bx[5] = -1e300;
    for (const Vec3f& p : v) {
      bx[0] = std::min<double>(bx[0], p.x), bx[1] = std::min<double>(bx[1], p.y), bx[2] = std::min<double>(bx[2], p.z);
      bx[3] = std::max<double>(bx[3], p.x), bx[4] = std::max<double>(bx[4], p.y), bx[5] = std::max<double>(bx[5], p.z);
    }
    for (int k = 0; k < 3; ++k) bx[k] -= widen, bx[k + 3] += widen;
  };
  const auto meets = [](const float* t, const double* o) {
    return !(t[0] > o[3] || t[1] > o[4] || t[2] > o[5] || t[3] < o[0] || t[4] < o[1] || t[5] < o[2]);
  };
  // The float plane pre-test below rejects only pairs more than this beyond the clearance.
  const float margin = static_cast<float>(c) + kPlaneSlack;
  const auto pair_touches = [&](const Vec3f* p, const Vec3f* q) { return c > 0 ? triangles_within(p, q, c) : triangles_intersect(p, q); };
  double box_a[6], box_b[6];
  organ_box(x.va, box_a, c);
  organ_box(x.vb, box_b, c);
  x.boxes_b.clear();
  x.near_b.clear();
  x.planes_b.clear();
  float bx[6];
  // With a witness, start both loops at its triangles: a touching pair is likely near the one
  // that touched last (the answer is the same in any order).
  const bool seen = witness && witness->latest >= 0 && witness->tri_a[witness->latest] < ta && witness->tri_b[witness->latest] < tb;
  const std::size_t start_a = seen ? static_cast<std::size_t>(witness->tri_a[witness->latest]) : 0;
  const std::size_t start_b = seen ? static_cast<std::size_t>(witness->tri_b[witness->latest]) : 0;
  for (std::size_t jj = 0; jj < tb; ++jj) {
    const std::size_t j = spiral(start_b, jj, tb);
    tri_box(x.vb, mb.indices, j, bx);
    if (!meets(bx, box_a)) continue;
    x.near_b.push_back(static_cast<std::uint32_t>(j));
    x.boxes_b.insert(x.boxes_b.end(), bx, bx + 6);
    x.planes_b.push_back(TrianglePlane::of(x.vb[mb.indices[3 * j]], x.vb[mb.indices[3 * j + 1]], x.vb[mb.indices[3 * j + 2]], margin));
  }
  if (!x.near_b.empty()) {
    for (std::size_t ii = 0; ii < ta; ++ii) {
      const std::size_t i = spiral(start_a, ii, ta);
      tri_box(x.va, ma.indices, i, bx);
      if (!meets(bx, box_b)) continue;
      const Vec3f tri_a[3] = {x.va[ma.indices[3 * i]], x.va[ma.indices[3 * i + 1]], x.va[ma.indices[3 * i + 2]]};
      const TrianglePlane plane_a = TrianglePlane::of(tri_a[0], tri_a[1], tri_a[2], margin);
      // Box of a's triangle, widened by the clearance in double (exact for touching boxes).
      const double lo[3] = {bx[0] - c, bx[1] - c, bx[2] - c}, hi[3] = {bx[3] + c, bx[4] + c, bx[5] + c};
      for (std::size_t k = 0; k < x.near_b.size(); ++k) {
        const float* b6 = &x.boxes_b[6 * k];
        if (b6[0] > hi[0] || b6[1] > hi[1] || b6[2] > hi[2] || b6[3] < lo[0] || b6[4] < lo[1] || b6[5] < lo[2]) continue;
        const std::uint32_t j = x.near_b[k];
        const Vec3f tri_b[3] = {x.vb[mb.indices[3 * j]], x.vb[mb.indices[3 * j + 1]], x.vb[mb.indices[3 * j + 2]]};
        if (x.planes_b[k].beyond(tri_a) || plane_a.beyond(tri_b)) continue;
        if (pair_touches(tri_a, tri_b)) {
          if (witness) witness->remember(i, j);
          return true;
        }
      }
    }
  }
  // No surfaces meet: one organ may still lie wholly inside the other's solid.
  if (is_solid(rb.prototype) && !x.va.empty() &&
      point_in_convex(d3(x.va[0]), x.vb.data(), mb.indices.data(), static_cast<int>(tb)))
    return true;
  if (is_solid(ra.prototype) && !x.vb.empty() &&
      point_in_convex(d3(x.vb[0]), x.va.data(), ma.indices.data(), static_cast<int>(ta)))
    return true;
  return false;
}

}  // namespace canopy
