#include "geometry/stand_metrics.hpp"

#include "geometry/organ_mesh.hpp"

#include <stdexcept>

namespace canopy {

std::vector<double> leaflet_area_per_plant(const Stand& s, PrototypeLibrary& lib) {
  std::vector<double> a(s.plant_count(), 0);
  for (std::size_t i = 0; i < s.organ_count(); ++i)
    if (s.organs[i].kind == OrganKind::leaflet) a[static_cast<std::size_t>(s.organs[i].plant)] += organ_area(s, i, lib);
  return a;
}

LeafAreaIndex leaf_area_index(const Stand& s, PrototypeLibrary& lib, int rows, int per_row, double plant_spacing,
                              double row_spacing) {
  if (rows < 1 || per_row < 1 || static_cast<std::size_t>(rows) * static_cast<std::size_t>(per_row) != s.plant_count())
    throw std::invalid_argument("leaf_area_index: the stand is not rows x per_row plants");
  if (!(plant_spacing > 0) || !(row_spacing > 0)) throw std::invalid_argument("leaf_area_index: spacings must be positive");
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

}  // namespace canopy
