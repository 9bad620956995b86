#pragma once
/// Triangles of one organ, made on the fly from its prototype and transform (never stored for a
/// whole stand): positions in the plant frame (relative to the plant origin), unit normals.
#include "geometry/prototype.hpp"
#include "geometry/stand.hpp"

#include <functional>
#include <string>
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

/// Makes every mesh the stand's organs use, before threads share the library (which ones: found
/// on `threads` threads, 0 = OpenMP's default; a level of detail out of range is left to the
/// library to report, organ by organ in order). Per mesh slot (mesh_slot), the mesh where the
/// stand uses it, null where it does not.
std::vector<const PrototypeMesh*> make_meshes(const Stand& stand, PrototypeLibrary& library, int threads = 0);

/// Fills `out` with organ `id` of `stand` (normals too unless `positions_only`).
void organ_mesh(const Stand& stand, std::size_t id, PrototypeLibrary& library, OrganMesh& out,
                bool positions_only = false);

/// The cofactor matrix of m's linear part (columns c1 x c2, c2 x c0, c0 x c1): it carries surface
/// normals and area elements, computed once per organ.
Affine3f cofactor(const Affine3f& m);
/// transform_normal with a precomputed cofactor matrix.
Vec3f transform_normal(const Affine3f& m, const Affine3f& cof, Vec3f n);

/// Calls `write(begin, end, buffer)` for consecutive ranges of [0, n) on all threads, a wave of
/// ranges at a time, and writes the buffers to `out` in order: parallel formatting, ordered output.
void write_ordered(class AtomicFile& out, std::size_t n, std::size_t chunk,
                   const std::function<void(std::size_t, std::size_t, std::string&)>& write);

/// One-sided blade area for leaflets and disks, outer surface area for cylinders and spheres (m2).
double organ_area(const Stand& stand, std::size_t id, PrototypeLibrary& library);
/// Length along the heading: cylinder and leaflet length, sphere and disk diameter (m).
double organ_length(const Stand& stand, std::size_t id);

/// Colour of each organ kind in exports and pictures (linear RGB).
Vec3f kind_colour(OrganKind k);

}  // namespace canopy
