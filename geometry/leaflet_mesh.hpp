#pragma once
/// The curved leaflet's mesh (geometry/leaflet_shape.hpp says what its angles mean; prototype.cpp
/// finishes its box and lanes). The flat blade's outline, stations and UVs, its points carried
/// onto a surface that keeps lengths: across the blade a circular arc rising at `fold` from the
/// midrib and turning by `cup` out to a half-width of 0.5; along it the midrib a circular arc of
/// length 1 turning by `bend`, the cross-section standing on the midrib's normal. Lengths along
/// and across are kept in a leaflet whose width is kNominalLeafletAspect of its length.
#include "geometry/leaflet_shape.hpp"

namespace canopy {

struct PrototypeMesh;

/// The mesh of a curved leaflet at level of detail `lod` (no box or lanes yet); its vertex
/// normals are the surface's (at the midrib of a folded blade, the mean of both halves').
PrototypeMesh curved_leaflet(int lod, const LeafletShape& shape);

}  // namespace canopy
