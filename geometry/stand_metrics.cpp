#include "geometry/stand_metrics.hpp"

#include "geometry/organ_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace canopy {

std::vector<double> leaflet_area_per_plant(const Stand& s, PrototypeLibrary& lib) {
  std::vector<double> a(s.plant_count(), 0);
  for (std::size_t i = 0; i < s.organ_count(); ++i)
    if (s.organs[i].kind == OrganKind::leaflet)
      a[static_cast<std::size_t>(s.organs[i].plant)] += organ_area(s, i, lib);
  return a;
}

LeafAreaIndex leaf_area_index(const Stand& s, PrototypeLibrary& lib, int rows, int per_row,
                              double plant_spacing, double row_spacing) {
  if (rows < 1 || per_row < 1 ||
      static_cast<std::size_t>(rows) * static_cast<std::size_t>(per_row) != s.plant_count())
    throw std::invalid_argument("leaf_area_index: the stand is not rows x per_row plants");
  if (!(plant_spacing > 0) || !(row_spacing > 0))
    throw std::invalid_argument("leaf_area_index: spacings must be positive");
  const std::vector<double> area = leaflet_area_per_plant(s, lib);
  LeafAreaIndex out;
  out.inner_only = rows >= 3 && per_row >= 3;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < per_row; ++c) {
      if (out.inner_only && (r == 0 || r == rows - 1 || c == 0 || c == per_row - 1)) continue;
      out.leaf_area += area[static_cast<std::size_t>(r * per_row + c)];
      ++out.plants;
    }
  out.ground_area = static_cast<double>(out.plants) * plant_spacing * row_spacing;
  out.lai = out.leaf_area / out.ground_area;
  return out;
}

LeafInclination leaf_inclination(const Stand& s, PrototypeLibrary& lib, int bins) {
  if (bins < 1) throw std::invalid_argument("leaf_inclination: at least one class");
  LeafInclination out;
  out.fraction.assign(static_cast<std::size_t>(bins), 0);
  OrganMesh m;
  double angle_area = 0;
  for (std::size_t i = 0; i < s.organ_count(); ++i) {
    if (s.organs[i].kind != OrganKind::leaflet) continue;
    organ_mesh(s, i, lib, m, true);
    const std::vector<std::uint32_t>& idx = m.prototype->indices;
    for (std::size_t t = 0; t < idx.size(); t += 3) {
      const Vec3d a = to_double(m.positions[idx[t]]), b = to_double(m.positions[idx[t + 1]]),
                  c = to_double(m.positions[idx[t + 2]]);
      const Vec3d n = cross(b - a, c - a);
      const double twice = length(n);
      if (!(twice > 0)) continue;
      const double deg = std::acos(std::min(1.0, std::fabs(n.z) / twice)) * 180 / std::numbers::pi;
      const int bin = std::min(bins - 1, static_cast<int>(deg / (90.0 / bins)));
      out.fraction[static_cast<std::size_t>(bin)] += 0.5 * twice;
      out.area += 0.5 * twice;
      angle_area += deg * 0.5 * twice;
    }
  }
  if (out.area > 0) {
    for (double& f : out.fraction) f /= out.area;
    out.mean_deg = angle_area / out.area;
  } else {
    for (double& f : out.fraction) f = std::numeric_limits<double>::quiet_NaN();
  }
  return out;
}

std::vector<double> plant_heights(const Stand& s, PrototypeLibrary& lib) {
  std::vector<double> h(s.plant_count(), 0);
  OrganMesh m;
  for (std::size_t i = 0; i < s.organ_count(); ++i) {
    organ_mesh(s, i, lib, m, true);
    double& top = h[static_cast<std::size_t>(s.organs[i].plant)];
    for (const Vec3f& v : m.positions) top = std::max(top, static_cast<double>(v.z));
  }
  return h;
}

}  // namespace canopy
