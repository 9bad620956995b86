#include "light/raster_stand.hpp"

#include "light/tally_grid.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace canopy::light {

bool left_out(const OrganRecord& r, const Affine3f& t) {
  const Vec3d a = to_double(t.c0), b = to_double(t.c1);
  if (std::abs(dot(cross(a, b), to_double(t.c2))) > 0) return false;
  const bool flat =
      r.prototype == PrototypeKind::disk || (r.prototype == PrototypeKind::leaflet && r.shape == 0);
  return !flat || !(length(cross(a, b)) > 0);
}

bool stand_box(const Stand& s, PrototypeLibrary& lib, Vec3d& lo_out, Vec3d& hi_out, std::size_t& left) {
  const double inf = std::numeric_limits<double>::infinity();
  Vec3d lo{inf, inf, inf}, hi{-inf, -inf, -inf};
  std::size_t out = 0;
  for (std::size_t i = 0; i < s.organ_count(); ++i) {
    const OrganRecord& r = s.organs[i];
    const Affine3f& t = s.transforms[i];
    if (left_out(r, t)) {
      ++out;
      continue;
    }
    // A flat blade's box has no depth, so its third column (whatever it is) moves no corner.
    const Box3f& bx = lib.get(r).box;
    const Vec3d off = s.offset(static_cast<std::size_t>(r.plant));
    for (int k = 0; k < 8; ++k) {
      const Vec3f p = apply(
          t, Vec3f{(k & 1) ? bx.hi.x : bx.lo.x, (k & 2) ? bx.hi.y : bx.lo.y, (k & 4) ? bx.hi.z : bx.lo.z});
      const Vec3d w = to_double(p) + off;
      lo = {std::min(lo.x, w.x), std::min(lo.y, w.y), std::min(lo.z, w.z)};
      hi = {std::max(hi.x, w.x), std::max(hi.y, w.y), std::max(hi.z, w.z)};
    }
  }
  left = out;
  if (!(lo.x <= hi.x)) return false;
  lo_out = lo, hi_out = hi;
  return true;
}

RasterStand::RasterStand(const Stand& s, PrototypeLibrary& lib, const OrganIndex& organs)
    : tri_first_(kMeshSlots, 0), tri_count_(kMeshSlots, 0), vertex_first_(kMeshSlots, 0),
      slot_(s.organ_count(), -1), offset_(s.plant_count()) {
  if (s.organ_count() >= std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("light: more organs than the rasterizer numbers (2^32 - 1)");
  std::vector<bool> used(kMeshSlots, false);
  for (std::size_t i = 0; i < s.organ_count(); ++i) {
    const OrganRecord& r = s.organs[i];
    if (left_out(r, s.transforms[i])) continue;
    const int slot = mesh_slot(r.prototype, r.lod, r.shape);
    slot_[i] = static_cast<std::int16_t>(slot);
    if (!used[static_cast<std::size_t>(slot)]) {
      used[static_cast<std::size_t>(slot)] = true;
      const PrototypeMesh& m = lib.get(r);
      const auto k = static_cast<std::size_t>(slot);
      vertex_first_[k] = static_cast<std::uint32_t>(positions_.size());
      tri_first_[k] = static_cast<std::uint32_t>(indices_.size() / 3);
      tri_count_[k] = static_cast<std::uint32_t>(m.triangle_count());
      positions_.insert(positions_.end(), m.positions.begin(), m.positions.end());
      indices_.insert(indices_.end(), m.indices.begin(), m.indices.end());
    }
    triangles_ += tri_count_[static_cast<std::size_t>(slot)];
  }
  for (std::size_t p = 0; p < s.plant_count(); ++p) offset_[p] = s.offset(p);
  view_.positions = positions_.data(), view_.indices = indices_.data();
  view_.slot_tri_first = tri_first_.data(), view_.slot_tri_count = tri_count_.data();
  view_.slot_vertex_first = vertex_first_.data();
  view_.transforms = s.transforms.data(), view_.slot = slot_.data(), view_.plant = organs.plant.data();
  view_.kind = organs.kind.data();
  view_.offset = offset_.data();
  view_.organs = s.organ_count(), view_.plants = s.plant_count(), view_.vertices = positions_.size();
  view_.mesh_triangles = indices_.size() / 3, view_.slots = kMeshSlots;
  static std::atomic<std::uint64_t> made{0};
  view_.generation = ++made;
}

RasterGrid raster_grid(const DirectionJob& job) {
  RasterGrid r;
  const Grid& g = job.grid;
  r.x0 = g.region.x0, r.y0 = g.region.y0;
  r.cw = g.region.width() / static_cast<double>(g.nx), r.ch = g.region.height() / static_cast<double>(g.ny);
  r.nx = static_cast<std::int64_t>(g.nx), r.ny = static_cast<std::int64_t>(g.ny);
  r.base = mix64(job.seed ^ mix64(job.stream * 0xd1b54a32d192ed03ULL));
  r.kx = -job.toward.x / job.toward.z, r.ky = -job.toward.y / job.toward.z;
  r.periodic = job.periodic;
  return r;
}

void rasterize(const RasterView& v, const RasterGrid& g, std::uint64_t* cells) {
  const auto put = [cells](std::uint64_t c, std::uint64_t key) {
    std::atomic_ref<std::uint64_t> cell(cells[c]);
    std::uint64_t now = cell.load(std::memory_order_relaxed);
    while (now < key && !cell.compare_exchange_weak(now, key, std::memory_order_relaxed)) {
    }
  };
  const auto n = static_cast<std::int64_t>(v.organs);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t o = 0; o < n; ++o) {
    auto p = put;
    raster_organ(g, v, static_cast<std::uint64_t>(o), p);
  }
}

Outcome outcome_of(std::int64_t organ, double z, const OrganIndex& organs, double layer_m,
                   std::size_t layers) {
  return hit_outcome(organ, z, organs.plant.data(), organs.kind.data(), layer_m,
                     static_cast<std::int32_t>(layers));
}

Tally tally_cells(const std::uint64_t* cells, const DirectionJob& job, const OrganIndex& organs,
                  std::size_t plants) {
  const std::uint64_t nx = job.grid.nx;
  return tally_grid(job.grid, plants, job.layers, 16, [&](std::uint64_t i, std::uint64_t j) {
    const std::uint64_t key = cells[j * nx + i];
    return outcome_of(key_organ(key), key_height(key), organs, job.layer_m, job.layers);
  });
}

}  // namespace canopy::light
