#pragma once
/// Prototype meshes in their own local frames (docs/design.md "Organs"): x along the organ's heading H,
/// y along its width direction L, z along its normal U. An organ is a prototype plus the 3x4
/// transform whose columns are H, L, U scaled by the organ's parameters and whose translation is
/// its joint, so every organ of a kind and level of detail shares one mesh.
///   cylinder: x in [0, 1], radius 1, capped and closed
///   leaflet:  flat ovate, pointed blade from (0,0,0) to (1,0,0), widest 1 (so y in [-0.5, 0.5]), z = 0;
///             a curved leaflet (shape code 1-255, geometry/leaflet_shape.hpp) is the same blade
///             bent along its midrib, cupped across it and folded at it, its midrib 1 long
///   sphere:   radius 1 centred at (1, 0, 0)
///   disk:     radius 1 centred at the origin in the x-y plane
#include "geometry/leaflet_shape.hpp"
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
  Box3f box;                                                // local box (exact bounds of the vertices)
  std::size_t triangle_count() const { return indices.size() / 3; }
};

/// Default level of detail: about 8,000 triangles for a default tomato plant.
inline constexpr int kDefaultLod = 2;
inline constexpr int kMaxLod = 16;

/// The mesh of `kind` at level of detail `lod` (1 = coarsest): leaflet outline stations 4*lod+1
/// (2*(4*lod) outline points), cylinder sides 4*lod, sphere 4*lod meridians and 2*lod+1 bands,
/// disk 8*lod sides. `shape` (leaflets only; geometry/leaflet_shape.hpp): 0 the flat blade;
/// a curved one has the same stations along the midrib and, where it is cupped or folded, rows
/// across it (the midrib and lod columns a side when cupped, the midrib alone when only folded).
PrototypeMesh make_prototype(PrototypeKind kind, int lod, std::uint8_t shape = 0);

/// The slot of the mesh of (prototype, lod, shape) among kMeshKinds x (kMaxLod + 1), as both
/// backends index their tables of meshes and boxes.
CANOPY_HD inline int mesh_slot(PrototypeKind prototype, int lod, int shape) {
  return mesh_kind(static_cast<int>(prototype), shape) * (kMaxLod + 1) + lod;
}
inline constexpr int kMeshSlots = kMeshKinds * (kMaxLod + 1);

/// Half-width of the unit leaflet blade at s in [0, 1] along its length: w(s) = N s^0.5 (1 - s),
/// ovate (widest at s = 1/3) with a pointed tip; N makes the widest point 0.5.
double leaflet_half_width(double s);
/// Area of the analytic unit leaflet outline: 2 * integral of leaflet_half_width (= 0.6928...).
double leaflet_outline_area();

/// Meshes of every prototype and level of detail used, made once on first use; safe to share
/// between threads (reads of a made mesh take no lock).
class PrototypeLibrary {
 public:
  /// Inline for a mesh made before (the exact tests ask millions of times). A shape other than 0
  /// is a curved leaflet's (any other prototype with one is refused).
  const PrototypeMesh& get(PrototypeKind kind, int lod, std::uint8_t shape = 0) {
    if (lod >= 1 && lod <= kMaxLod && (shape == 0 || kind == PrototypeKind::leaflet))
      if (const PrototypeMesh* m =
              made_[static_cast<std::size_t>(mesh_slot(kind, lod, shape))].load(std::memory_order_acquire))
        return *m;
    return make(kind, lod, shape);
  }
  /// The mesh of an organ (its prototype, level of detail and shape).
  template <typename Record>
  const PrototypeMesh& get(const Record& r) {
    return get(r.prototype, r.lod, r.shape);
  }

 private:
  const PrototypeMesh& make(PrototypeKind kind, int lod, std::uint8_t shape);
  std::mutex mutex_;
  std::array<std::atomic<const PrototypeMesh*>, kMeshSlots> made_{};
  std::vector<std::unique_ptr<PrototypeMesh>> owned_;
};

/// One-sided area of the mesh of `m` carried by `t` (for leaflets and disks the blade area).
double transformed_area(const PrototypeMesh& m, const Affine3f& t);

}  // namespace canopy
