#pragma once
/// Triangles of one organ, made on the fly from its prototype and transform (never stored for a
/// whole stand): positions in the plant frame (relative to the plant origin), unit normals.
#include "geometry/prototype.hpp"
#include "geometry/stand.hpp"

#include <vector>

namespace canopy {

/// The normal of a surface carried by m: the cofactor matrix of m's linear part times n, so
/// non-uniform scale keeps normals perpendicular; a degenerate map falls back to the column that
/// survives (or +Z).
Vec3f transform_normal(const Affine3f& m, Vec3f n);

struct OrganMesh {
  const PrototypeMesh* prototype = nullptr;
  std::vector<Vec3f> positions;  // plant frame
  std::vector<Vec3f> normals;
};

/// Fills `out` with organ `id` of `stand`.
void organ_mesh(const Stand& stand, std::size_t id, PrototypeLibrary& library, OrganMesh& out);

/// One-sided blade area for leaflets and disks, outer surface area for cylinders and spheres (m2).
double organ_area(const Stand& stand, std::size_t id, PrototypeLibrary& library);
/// Length along the heading: cylinder and leaflet length, sphere and disk diameter (m).
double organ_length(const Stand& stand, std::size_t id);

/// Colour of each organ kind in exports and pictures (linear RGB).
Vec3f kind_colour(OrganKind k);

}  // namespace canopy
