#include "geometry/leaf_angles.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace canopy {

LeafAngleSums& LeafAngleSums::operator+=(const LeafAngleSums& o) {
  area += o.area;
  for (std::size_t i = 0; i < bins.size(); ++i) bins[i] += o.bins[i];
  inclination_area += o.inclination_area;
  for (std::size_t i = 0; i < g_area.size(); ++i) g_area[i] += o.g_area[i];
  return *this;
}

double mean_projection(double zenith, double inclination) {
  const double a = std::cos(zenith) * std::cos(inclination), b = std::sin(zenith) * std::sin(inclination);
  if (b <= a) return a;  // the blade faces the direction at every azimuth
  const double phi0 = std::acos(std::clamp(-a / b, -1.0, 1.0));
  return (a * (2 * phi0 - std::numbers::pi) + 2 * b * std::sin(phi0)) / std::numbers::pi;
}

std::vector<LeafAngleSums> leaf_angle_sums(const Stand& s, PrototypeLibrary& lib) {
  std::vector<LeafAngleSums> out(s.plant_count());
  // Meshes made before the threads share the library.
  for (std::size_t i = 0; i < s.organ_count(); ++i)
    if (s.organs[i].kind == OrganKind::leaflet) lib.get(s.organs[i].prototype, s.organs[i].lod);
  std::array<double, kGZenithsDeg.size()> zenith{};
  for (std::size_t k = 0; k < zenith.size(); ++k) zenith[k] = kGZenithsDeg[k] * std::numbers::pi / 180;
#pragma omp parallel for schedule(dynamic, 4)
  for (std::size_t p = 0; p < s.plant_count(); ++p) {
    LeafAngleSums& sum = out[p];
    const PlantRecord& plant = s.plants[p];
    for (std::size_t i = plant.first_organ; i < plant.first_organ + plant.organ_count; ++i) {
      if (s.organs[i].kind != OrganKind::leaflet) continue;
      const PrototypeMesh& m = lib.get(s.organs[i].prototype, s.organs[i].lod);
      const Affine3f& t = s.transforms[i];
      // A u x A v = cof(A) (u x v): each triangle's area vector from its local cross product.
      const Vec3d c0 = to_double(t.c0), c1 = to_double(t.c1), c2 = to_double(t.c2);
      const Vec3d k0 = cross(c1, c2), k1 = cross(c2, c0), k2 = cross(c0, c1);
      for (const Vec3f& f : m.face_cross) {
        const Vec3d n = k0 * f.x + k1 * f.y + k2 * f.z;
        const double len = length(n);
        if (!(len > 0)) continue;
        const double area = 0.5 * len;
        const double incl = std::acos(std::min(1.0, std::abs(n.z) / len));
        const double deg = incl * 180 / std::numbers::pi;
        sum.area += area;
        sum.bins[static_cast<std::size_t>(std::clamp(static_cast<int>(deg / kLeafAngleBinDeg), 0, kLeafAngleBins - 1))] += area;
        sum.inclination_area += deg * area;
        for (std::size_t k = 0; k < zenith.size(); ++k) sum.g_area[k] += area * mean_projection(zenith[k], incl);
      }
    }
  }
  return out;
}

LeafAngles leaf_angles(const LeafAngleSums& t) {
  LeafAngles a;
  a.leaf_area = t.area;
  a.area = t.bins;
  if (!(t.area > 0)) return a;
  for (std::size_t i = 0; i < a.fraction.size(); ++i) a.fraction[i] = t.bins[i] / t.area;
  a.mean_inclination_deg = t.inclination_area / t.area;
  for (std::size_t k = 0; k < a.g.size(); ++k) a.g[k] = t.g_area[k] / t.area;
  return a;
}

LeafAngles leaf_angles(const std::vector<LeafAngleSums>& per_plant) {
  LeafAngleSums total;
  for (const LeafAngleSums& s : per_plant) total += s;
  return leaf_angles(total);
}

}  // namespace canopy
