#pragma once
/// A stand as Embree sees it, shared by canopy light and canopy render: each mesh (prototype,
/// level of detail and, for a leaflet, its curved shape) is one Embree scene, and each organ an
/// instance of it carried by its transform (plant offset added), with the organ's index as the
/// instance id. A 10,000-plant stand costs a few hundred bytes per organ, not a copy of its tens
/// of millions of triangles.
#include "geometry/prototype.hpp"
#include "geometry/stand.hpp"

#include <embree3/rtcore.h>

#include <cstddef>
#include <vector>

namespace canopy::light {

class EmbreeStand {
 public:
  /// Embree builds with the run's OpenMP team (--threads N means N throughout). Throws
  /// std::runtime_error when Embree cannot start or build the scene.
  EmbreeStand(const Stand& stand, PrototypeLibrary& lib);
  ~EmbreeStand() { release(); }
  EmbreeStand(const EmbreeStand&) = delete;
  EmbreeStand& operator=(const EmbreeStand&) = delete;

  RTCScene scene() const { return top_; }
  /// The union of the instanced organs' boxes (metres, relative to stand_origin); false when no
  /// organ is in the scene.
  bool bounds(Vec3d& lo, Vec3d& hi) const;
  /// Organs left out because their transform flattens a solid to nothing.
  std::size_t skipped() const { return skipped_; }

 private:
  void build(const Stand& stand, PrototypeLibrary& lib);
  void release();
  RTCDevice device_ = nullptr;
  RTCScene top_ = nullptr;
  std::vector<RTCScene> meshes_;
  Vec3d lo_, hi_;
  std::size_t skipped_ = 0;
};

}  // namespace canopy::light
