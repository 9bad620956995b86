#include "light/leaf_layers.hpp"

#include <algorithm>
#include <cmath>

namespace canopy::light {

std::vector<double> layer_leaf_area(const Stand& s, PrototypeLibrary& lib, double layer_m,
                                    std::size_t layers) {
  std::vector<std::vector<double>> per_plant(s.plant_count());
  for (std::size_t i = 0; i < s.organ_count(); ++i)
    if (s.organs[i].kind == OrganKind::leaflet) lib.get(s.organs[i]);
#pragma omp parallel for schedule(dynamic, 4)
  for (std::size_t p = 0; p < s.plant_count(); ++p) {
    std::vector<double>& a = per_plant[p];
    a.assign(layers, 0);
    const PlantRecord& plant = s.plants[p];
    for (std::size_t i = plant.first_organ; i < plant.first_organ + plant.organ_count; ++i) {
      if (s.organs[i].kind != OrganKind::leaflet) continue;
      const PrototypeMesh& m = lib.get(s.organs[i]);  // a curved leaflet's own mesh
      const Affine3f& t = s.transforms[i];
      for (std::size_t k = 0; k + 2 < m.indices.size(); k += 3) {
        const Vec3d p0 = to_double(apply(t, m.positions[m.indices[k]])),
                    p1 = to_double(apply(t, m.positions[m.indices[k + 1]])),
                    p2 = to_double(apply(t, m.positions[m.indices[k + 2]]));
        const double area = 0.5 * length(cross(p1 - p0, p2 - p0));
        const double z = (p0.z + p1.z + p2.z) / 3;
        a[static_cast<std::size_t>(std::clamp(static_cast<long>(std::floor(z / layer_m)), 0L,
                                              static_cast<long>(layers) - 1))] += area;
      }
    }
  }
  std::vector<double> out(layers, 0);
  for (const auto& a : per_plant)
    for (std::size_t l = 0; l < layers; ++l) out[l] += a[l];
  return out;
}

}  // namespace canopy::light
