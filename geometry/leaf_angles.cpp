#include "geometry/leaf_angles.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace canopy {

LeafAngleSums& LeafAngleSums::operator+=(const LeafAngleSums& o) {
  area += o.area;
  for (std::size_t i = 0; i < bins.size(); ++i) bins[i] += o.bins[i];
  inclination_area += o.inclination_area;
  for (std::size_t i = 0; i < g_area.size(); ++i) g_area[i] += o.g_area[i];
  return *this;
}

namespace {

/// mean_projection from the cosines and sines of the two angles.
double projection(double cz, double sz, double cl, double sl) {
  const double a = cz * cl, b = sz * sl;
  if (b <= a) return a;  // the blade faces the direction at every azimuth
  const double phi0 = std::acos(std::clamp(-a / b, -1.0, 1.0));
  return (a * (2 * phi0 - std::numbers::pi) + 2 * b * std::sin(phi0)) / std::numbers::pi;
}

/// Adds `area` of blade whose unit-length normal has vertical component `nz`.
void add_blade(LeafAngleSums& sum, double area, double nz, const std::array<double, kGZenithsDeg.size()>& cz,
               const std::array<double, kGZenithsDeg.size()>& sz) {
  const double cl = std::min(1.0, std::abs(nz)), sl = std::sqrt(std::max(0.0, 1 - cl * cl));
  const double deg = std::acos(cl) * 180 / std::numbers::pi;
  sum.area += area;
  sum.bins[static_cast<std::size_t>(
      std::clamp(static_cast<int>(deg / kLeafAngleBinDeg), 0, kLeafAngleBins - 1))] += area;
  sum.inclination_area += deg * area;
  for (std::size_t k = 0; k < cz.size(); ++k) sum.g_area[k] += area * projection(cz[k], sz[k], cl, sl);
}

}  // namespace

double mean_projection(double zenith, double inclination) {
  return projection(std::cos(zenith), std::sin(zenith), std::cos(inclination), std::sin(inclination));
}

std::vector<LeafAngleSums> leaf_angle_sums(const Stand& s, PrototypeLibrary& lib) {
  std::vector<LeafAngleSums> out(s.plant_count());
  // Meshes made before the threads share the library.
  for (std::size_t i = 0; i < s.organ_count(); ++i)
    if (s.organs[i].kind == OrganKind::leaflet) lib.get(s.organs[i]);
  std::array<double, kGZenithsDeg.size()> cz{}, sz{};
  for (std::size_t k = 0; k < cz.size(); ++k)
    cz[k] = std::cos(kGZenithsDeg[k] * std::numbers::pi / 180),
    sz[k] = std::sin(kGZenithsDeg[k] * std::numbers::pi / 180);
#pragma omp parallel for schedule(dynamic, 4)
  for (std::size_t p = 0; p < s.plant_count(); ++p) {
    LeafAngleSums& sum = out[p];
    const PlantRecord& plant = s.plants[p];
    for (std::size_t i = plant.first_organ; i < plant.first_organ + plant.organ_count; ++i) {
      if (s.organs[i].kind != OrganKind::leaflet) continue;
      const PrototypeKind proto = s.organs[i].prototype;
      const PrototypeMesh& m = lib.get(s.organs[i]);  // a curved leaflet's own mesh
      const Affine3f& t = s.transforms[i];
      // A u x A v = cof(A) (u x v): each triangle's area vector from its local cross product.
      const Vec3d c0 = to_double(t.c0), c1 = to_double(t.c1), c2 = to_double(t.c2);
      const Vec3d k0 = cross(c1, c2), k1 = cross(c2, c0), k2 = cross(c0, c1);
      if ((proto == PrototypeKind::leaflet && s.organs[i].shape == 0) || proto == PrototypeKind::disk) {
        // A flat blade (local z = 0): every triangle's area vector is k2 times its local one.
        const double len = length(k2);
        if (!(len > 0)) continue;
        double local = 0;
        for (const Vec3f& f : m.face_cross) local += std::abs(static_cast<double>(f.z));
        add_blade(sum, 0.5 * len * local, k2.z / len, cz, sz);
        continue;
      }
      for (const Vec3f& f : m.face_cross) {
        const Vec3d n = k0 * f.x + k1 * f.y + k2 * f.z;
        const double len = length(n);
        if (len > 0) add_blade(sum, 0.5 * len, n.z / len, cz, sz);
      }
    }
  }
  return out;
}

LeafAngles leaf_angles(const LeafAngleSums& t) {
  LeafAngles a;
  a.leaf_area = t.area;
  a.area = t.bins;
  // No leaflet area: the fractions, mean and G are undefined (NaN, null in JSON), not 0.
  if (!(t.area > 0)) {
    const double none = std::numeric_limits<double>::quiet_NaN();
    a.fraction.fill(none), a.g.fill(none), a.mean_inclination_deg = none;
    return a;
  }
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
