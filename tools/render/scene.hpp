#pragma once
/// Pictures of a stand, ray cast with Embree (Intel's ray tracing kernels, Debian libembree-dev):
/// each prototype mesh is one Embree scene, and each organ an instance of it carried by its
/// transform (plant offset added), so a 10,000-plant stand costs a few hundred bytes per organ,
/// not a copy of its 75 million triangles. Orthographic cameras: an oblique view from the
/// front-left, a view from above and a level view from the side; organs coloured by kind, Lambert-shaded from
/// both sides, the highlighted organs (contacts) in magenta, the soil below.
#include "geometry/prototype.hpp"
#include "geometry/stand.hpp"
#include "tools/render/image.hpp"

#include <cstdint>
#include <memory>
#include <vector>

namespace canopy::render {

/// oblique: from the front-left and above; top: from above; side: level, along the rows' normal (+Y).
enum class View { oblique, top, side };

/// The colour of highlighted organs: magenta, far from every kind colour.
inline constexpr float kContactColour[3] = {1.0f, 0.0f, 0.85f};

struct Camera {
  Vec3d centre, dir, right, up;
  double half_w = 1, half_h = 1, back = 1;
  int width = 1, height = 1;
  /// The pixel (column, row; row 0 at the top) a world point (relative to stand_origin) lands on.
  void project(Vec3d p, double& col, double& row) const;
};

/// A camera looking at the box [lo, hi] (metres, relative to stand_origin) from `view`, fitted
/// with a small margin to an image of width x height.
Camera fit_camera(Vec3d lo, Vec3d hi, View view, int width, int height);

class Scene {
 public:
  /// Throws std::runtime_error when Embree cannot start.
  Scene(const Stand& stand, PrototypeLibrary& lib);
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;
  /// The stand's bounds (metres, relative to stand_origin).
  Vec3d lo() const { return lo_; }
  Vec3d hi() const { return hi_; }
  /// One picture; `highlight` flags organs drawn in the contact colour (may be empty).
  Image render(const Camera& camera, const std::vector<std::uint8_t>& highlight) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  const Stand& stand_;
  Vec3d lo_, hi_;
};

}  // namespace canopy::render
