#pragma once
// Stand.grow's `positions` argument read into placements (tools/python/positions_array.cpp).
#include "tools/python/common.hpp"

#include "geometry/layout.hpp"

#include <vector>

#pragma GCC visibility push(hidden)
namespace canopy::python {

/// Rows x, y, rotation (degrees), seed from an N x 4 NumPy array (any numeric dtype) or a list
/// of rows; every seed the whole number given (std::invalid_argument past what a float holds).
std::vector<PlantPlacement> placements_of(const py::object& positions);

}  // namespace canopy::python
#pragma GCC visibility pop
