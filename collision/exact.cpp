#include "collision/exact.hpp"

#include "collision/mbvt.hpp"
#include "geometry/triangle_test.hpp"

#include <cassert>

namespace canopy {

void organ_vertices(const Stand& s, const PrototypeMesh& mesh, std::int32_t organ, std::int32_t frame_plant,
                    std::vector<Vec3f>& out) {
  const Affine3f& m = s.transforms[static_cast<std::size_t>(organ)];
  const std::int32_t plant = s.organs[static_cast<std::size_t>(organ)].plant;
  const Vec3f d = plant == frame_plant ? Vec3f{0, 0, 0} : plant_offset(s, frame_plant, plant);
  out.resize(mesh.positions.size());
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) out[i] = apply(m, mesh.positions[i]) + d;
}

bool organs_touch(const Stand& s, PrototypeLibrary& lib, std::int32_t a, std::int32_t b, float clearance, ExactScratch& x) {
  assert(a < b);
  const OrganRecord& ra = s.organs[static_cast<std::size_t>(a)];
  const OrganRecord& rb = s.organs[static_cast<std::size_t>(b)];
  const PrototypeMesh& ma = lib.get(ra.prototype, ra.lod);
  const PrototypeMesh& mb = lib.get(rb.prototype, rb.lod);
  organ_vertices(s, ma, a, ra.plant, x.va);
  organ_vertices(s, mb, b, ra.plant, x.vb);
  const std::size_t ta = ma.triangle_count(), tb = mb.triangle_count();
  const double c = clearance;
  x.boxes_b.resize(6 * tb);
  for (std::size_t j = 0; j < tb; ++j) {
    const Vec3f p = x.vb[mb.indices[3 * j]], q = x.vb[mb.indices[3 * j + 1]], r = x.vb[mb.indices[3 * j + 2]];
    float* bx = &x.boxes_b[6 * j];
    bx[0] = min_f(p.x, min_f(q.x, r.x)), bx[1] = min_f(p.y, min_f(q.y, r.y)), bx[2] = min_f(p.z, min_f(q.z, r.z));
    bx[3] = max_f(p.x, max_f(q.x, r.x)), bx[4] = max_f(p.y, max_f(q.y, r.y)), bx[5] = max_f(p.z, max_f(q.z, r.z));
  }
  for (std::size_t i = 0; i < ta; ++i) {
    const Vec3f tri_a[3] = {x.va[ma.indices[3 * i]], x.va[ma.indices[3 * i + 1]], x.va[ma.indices[3 * i + 2]]};
    // Box of a's triangle, widened by the clearance in double (exact for touching boxes).
    const double lo[3] = {min_f(tri_a[0].x, min_f(tri_a[1].x, tri_a[2].x)) - c, min_f(tri_a[0].y, min_f(tri_a[1].y, tri_a[2].y)) - c,
                          min_f(tri_a[0].z, min_f(tri_a[1].z, tri_a[2].z)) - c};
    const double hi[3] = {max_f(tri_a[0].x, max_f(tri_a[1].x, tri_a[2].x)) + c, max_f(tri_a[0].y, max_f(tri_a[1].y, tri_a[2].y)) + c,
                          max_f(tri_a[0].z, max_f(tri_a[1].z, tri_a[2].z)) + c};
    for (std::size_t j = 0; j < tb; ++j) {
      const float* bx = &x.boxes_b[6 * j];
      if (bx[0] > hi[0] || bx[1] > hi[1] || bx[2] > hi[2] || bx[3] < lo[0] || bx[4] < lo[1] || bx[5] < lo[2]) continue;
      const Vec3f tri_b[3] = {x.vb[mb.indices[3 * j]], x.vb[mb.indices[3 * j + 1]], x.vb[mb.indices[3 * j + 2]]};
      if (c > 0 ? triangles_within(tri_a, tri_b, c) : triangles_intersect(tri_a, tri_b)) return true;
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
