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

  /// Organs left out are those light/raster_stand.hpp's left_out() names; their box and count
  /// are stand_box()'s.
  RTCScene scene() const { return top_; }

 private:
  void build(const Stand& stand, PrototypeLibrary& lib);
  void release();
  RTCDevice device_ = nullptr;
  RTCScene top_ = nullptr;
  std::vector<RTCScene> meshes_;
};

}  // namespace canopy::light
