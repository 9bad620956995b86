#pragma once
/// Stand-level numbers crop modellers compare stands by.
#include "geometry/prototype.hpp"
#include "geometry/stand.hpp"

#include <cstddef>
#include <limits>
#include <vector>

namespace canopy {

struct LeafAreaIndex {
  double lai = 0;           // one-sided leaflet area / ground area of the plants counted
  double leaf_area = 0;     // m2, over the plants counted
  double ground_area = 0;   // m2
  std::size_t plants = 0;   // plants counted
  bool inner_only = false;  // true when edge plants were left out
};

/// Leaf area index (one-sided leaflet blade area over ground area) of a row stand of `rows` x
/// `per_row` plants (row-major, as row_layout places them), each plant owning
/// plant_spacing x row_spacing of ground. Counted on the inner plants (neither in the first or
/// last row nor first or last in its row), so the open edges of a small stand do not bias it;
/// a stand with fewer than 3 rows or 3 plants a row has no inner plants and counts every plant.
LeafAreaIndex leaf_area_index(const Stand& stand, PrototypeLibrary& lib, int rows, int per_row,
                              double plant_spacing, double row_spacing);

/// One-sided leaflet area of each plant, m2 (the exported meshes' areas).
std::vector<double> leaflet_area_per_plant(const Stand& stand, PrototypeLibrary& lib);

/// The leaf inclination distribution: the angle of each leaflet triangle's normal from the
/// vertical (0: a horizontal blade, 90: an upright one), weighted by the triangle's area, in
/// `bins` classes of 90 / bins degrees (fractions summing to 1), and its area-weighted mean. A
/// stand without leaflet area has no inclination: the mean and the fractions are NaN (a flat
/// blade would read 0).
struct LeafInclination {
  std::vector<double> fraction;
  double mean_deg = std::numeric_limits<double>::quiet_NaN();
  double area = 0;  // m2 of leaflet blade counted
};
LeafInclination leaf_inclination(const Stand& stand, PrototypeLibrary& lib, int bins = 9);

/// Each plant's height: the highest vertex of its organs above its origin, m.
std::vector<double> plant_heights(const Stand& stand, PrototypeLibrary& lib);

}  // namespace canopy
