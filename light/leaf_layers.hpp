#pragma once
/// The leaflet area of a stand by height layer, for the vertical profile of canopy light.
#include "geometry/prototype.hpp"
#include "geometry/stand.hpp"

#include <vector>

namespace canopy::light {

/// One-sided leaflet area in each of `layers` layers `layer_m` high from the ground, each triangle
/// in the layer of its centroid (the top layer takes what lies above, the first what lies
/// below); summed plant by plant in organ order, so the same on any thread count.
std::vector<double> layer_leaf_area(const Stand& stand, PrototypeLibrary& lib, double layer_m,
                                    std::size_t layers);

}  // namespace canopy::light
