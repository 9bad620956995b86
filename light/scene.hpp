#pragma once
/// The stand as Embree sees it for light: each prototype mesh is one Embree scene and each organ
/// an instance of it carried by its transform (plant offset added), as `canopy render` does, so
/// memory is a few hundred bytes per organ. A ray is traced through the stand and, when the
/// field is periodic, through every copy of the stand shifted by whole tiles that its path
/// crosses (nearest hit over all copies): exact for organs that overhang the tile by any amount.
#include "geometry/prototype.hpp"
#include "geometry/stand.hpp"

#include <cstdint>
#include <memory>

namespace canopy::light {

/// Coordinates are metres relative to the stand's origin (stand_origin), Z up.
struct Box2d {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  double width() const { return x1 - x0; }
  double height() const { return y1 - y0; }
  double area() const { return width() * height(); }
};

struct Hit {
  std::int64_t organ = -1;  // -1: the ray reached the ground
  double t = 0;             // distance along the ray
};

class Scene {
 public:
  /// The stand's bounds now; the Embree scene when first asked for (build()). Keeps references
  /// to `stand` and `lib`.
  Scene(const Stand& stand, PrototypeLibrary& lib);
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  /// The stand's bounds (organ boxes, z from at most 0).
  Vec3d lo() const { return lo_; }
  Vec3d hi() const { return hi_; }
  /// Organs left out of the scene because their transform flattens a solid to nothing.
  std::size_t skipped() const { return skipped_; }

  /// Makes the traces periodic over tiles of `size` (x, y; metres); size 0 switches it off.
  void set_period(double x, double y) { px_ = x, py_ = y; }

  /// Builds the Embree scene unless built (on the calling thread, before any trace): a run
  /// whose passes are all rasterized never needs it. Throws std::runtime_error when Embree
  /// cannot start or build it.
  void build();
  double build_s() const { return build_s_; }

  /// The nearest organ hit by the ray (build() first) from `org` along unit `dir` with t in [0, t_max].
  Hit trace(Vec3d org, Vec3d dir, double t_max) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  const Stand& stand_;
  PrototypeLibrary& lib_;
  double build_s_ = 0;
  Vec3d lo_, hi_;
  std::size_t skipped_ = 0;
  double px_ = 0, py_ = 0;
};

}  // namespace canopy::light
