#pragma once
/// Prototype meshes in their own local frames (DESIGN.md "Organs"): x along the organ's heading H,
/// y along its width direction L, z along its normal U. An organ is a prototype plus the 3x4
/// transform whose columns are H, L, U scaled by the organ's parameters and whose translation is
/// its joint, so every organ of a kind and level of detail shares one mesh.
///   cylinder: x in [0, 1], radius 1, capped and closed
///   leaflet:  flat ovate, pointed blade from (0,0,0) to (1,0,0), widest 1 (so y in [-0.5, 0.5]), z = 0
///   sphere:   radius 1 centred at (1, 0, 0)
///   disk:     radius 1 centred at the origin in the x-y plane
#include "geometry/line_aligned.hpp"
#include "geometry/organ_kind.hpp"
#include "geometry/vec.hpp"

#include <array>
#include <cstdint>
#include <atomic>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

namespace canopy {

struct Box3f {
  Vec3f lo, hi;
};

struct PrototypeMesh {
  std::vector<Vec3f> positions;
  std::vector<Vec3f> normals;
  std::vector<std::array<float, 2>> uvs;  // leaflets only
  std::vector<std::uint32_t> indices;     // triangles, counter-clockwise seen from the normal
  std::vector<Vec3f> face_cross;          // (b - a) x (c - a) per triangle, local frame
  /// The triangles' corners by groups of 8 triangles in lanes: per group 9 runs of 8 floats
  /// (first corner x y z, second, third), zeros past the last triangle. The host's exact stage
  /// poses 8 triangles at a time from them (collision/exact.cpp).
  LineAlignedVector<float> corner_lanes;
  static constexpr std::size_t kCornerGroupFloats = 9 * 8;  // floats of corner_lanes per group of 8 triangles
  Box3f box;                              // local box (exact bounds of the vertices)
  std::size_t triangle_count() const { return indices.size() / 3; }
};

/// Default level of detail: about 8,000 triangles for a default tomato plant.
inline constexpr int kDefaultLod = 2;
inline constexpr int kMaxLod = 16;

/// The mesh of `kind` at level of detail `lod` (1 = coarsest): leaflet outline stations 4*lod+1
/// (2*(4*lod) outline points), cylinder sides 4*lod, sphere 4*lod meridians and 2*lod+1 bands,
/// disk 8*lod sides.
PrototypeMesh make_prototype(PrototypeKind kind, int lod);

/// Half-width of the unit leaflet blade at s in [0, 1] along its length: w(s) = N s^0.5 (1 - s),
/// ovate (widest at s = 1/3) with a pointed tip; N makes the widest point 0.5.
double leaflet_half_width(double s);
/// Area of the analytic unit leaflet outline: 2 * integral of leaflet_half_width (= 0.6928...).
double leaflet_outline_area();

/// Meshes of every prototype and level of detail used, made once on first use; safe to share
/// between threads (reads of a made mesh take no lock).
class PrototypeLibrary {
 public:
  /// Inline for a mesh made before (the exact tests ask millions of times).
  const PrototypeMesh& get(PrototypeKind kind, int lod) {
    if (lod >= 1 && lod <= kMaxLod)
      if (const PrototypeMesh* m = made_[static_cast<std::size_t>(kind)][static_cast<std::size_t>(lod)].load(std::memory_order_acquire))
        return *m;
    return make(kind, lod);
  }

 private:
  const PrototypeMesh& make(PrototypeKind kind, int lod);
  std::mutex mutex_;
  std::array<std::array<std::atomic<const PrototypeMesh*>, kMaxLod + 1>, 4> made_{};
  std::vector<std::unique_ptr<PrototypeMesh>> owned_;
};

/// One-sided area of the mesh of `m` carried by `t` (for leaflets and disks the blade area).
double transformed_area(const PrototypeMesh& m, const Affine3f& t);

}  // namespace canopy
