#include "geometry/organ_mesh.hpp"

namespace canopy {

Vec3f transform_normal(const Affine3f& m, Vec3f n) {
  // Columns of the cofactor matrix of A = [c0 c1 c2] are c1 x c2, c2 x c0, c0 x c1.
  const Vec3f r = cross(m.c1, m.c2) * n.x + cross(m.c2, m.c0) * n.y + cross(m.c0, m.c1) * n.z;
  const float len = length(r);
  if (len > 0 && std::isfinite(len)) return r * (1 / len);
  const Vec3f d = apply_linear(m, n);  // degenerate (zero-length or zero-width) organ
  const float dl = length(d);
  if (dl > 0) return d * (1 / dl);
  return {0, 0, 1};
}

void organ_mesh(const Stand& stand, std::size_t id, PrototypeLibrary& library, OrganMesh& out) {
  const OrganRecord& r = stand.organs[id];
  const Affine3f& m = stand.transforms[id];
  out.prototype = &library.get(r.prototype, r.lod);
  const auto& pm = *out.prototype;
  out.positions.resize(pm.positions.size());
  out.normals.resize(pm.normals.size());
  for (std::size_t i = 0; i < pm.positions.size(); ++i) {
    out.positions[i] = apply(m, pm.positions[i]);
    out.normals[i] = transform_normal(m, pm.normals[i]);
  }
}

double organ_area(const Stand& stand, std::size_t id, PrototypeLibrary& library) {
  const OrganRecord& r = stand.organs[id];
  return transformed_area(library.get(r.prototype, r.lod), stand.transforms[id]);
}

double organ_length(const Stand& stand, std::size_t id) {
  const auto& p = stand.params[id];
  switch (stand.organs[id].prototype) {
    case PrototypeKind::cylinder:
    case PrototypeKind::leaflet: return p[0];
    case PrototypeKind::sphere:
    case PrototypeKind::disk: return 2.0 * p[0];
  }
  return 0;
}

Vec3f kind_colour(OrganKind k) {
  switch (k) {
    case OrganKind::internode: return {0.30f, 0.45f, 0.15f};
    case OrganKind::petiole: return {0.40f, 0.60f, 0.20f};
    case OrganKind::rachis: return {0.45f, 0.65f, 0.25f};
    case OrganKind::leaflet: return {0.10f, 0.50f, 0.10f};
    case OrganKind::peduncle: return {0.50f, 0.55f, 0.20f};
    case OrganKind::fruit: return {0.80f, 0.10f, 0.05f};
    case OrganKind::flower: return {0.95f, 0.85f, 0.10f};
  }
  return {0.5f, 0.5f, 0.5f};
}

}  // namespace canopy
