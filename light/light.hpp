#pragma once
/// Light interception of a stand (canopy light): the direct beam of each sun position, the
/// diffuse light of a discretised sky, ground cover and STAR, per stand, plant, organ kind and
/// height layer, each with its standard error. Rays are traced through the instanced stand
/// (light/scene.hpp), periodic over the tile by default so a small stand stands for a field.
///
/// Fractions are of the light falling on a horizontal surface: a direction's intercepted
/// fraction is the part of the light that would reach the tile's ground that organs stop first;
/// a plant's is its part of the light on its ground share (tile area / plants), so the mean over
/// plants is the stand's. Ground cover is the intercepted fraction of light from the zenith (the
/// vertically projected area over the ground area). STAR is the leaflets' silhouette area (seen
/// from a direction, hidden parts not counted) over their one-sided area, averaged over the sky
/// directions with the sky's weights.
#include "geometry/leaf_angles.hpp"
#include "geometry/prototype.hpp"
#include "geometry/stand.hpp"
#include "light/raster_device.hpp"
#include "light/scene.hpp"
#include "light/sky.hpp"
#include "light/tally.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace canopy::light {

struct Beam {
  double elevation_deg = 90, azimuth_deg = 0;
};

/// Limits on what a request may ask (each refused past it with a clear message).
inline constexpr double kMinError = 1e-5, kMaxError = 0.5;
inline constexpr double kMaxRaysPerDirection = 2e9;
inline constexpr std::size_t kMaxLayers = 100000;
/// Copies of the stand over any point of a periodic tile, at most: a tile far smaller than the
/// stand makes every ray cross that many copies of it (a 1 mm tile under a 1 m plant, a million).
inline constexpr double kMaxTileCopies = 1000;
/// Copies of the tile a ray's path may cross on its way down through the stand, at most: the
/// number grows as 1 / tan(elevation) towards the horizon, and tracing walks each (2 plants of
/// tomato_young on their 0.8 x 1 m tile, a sun at 0.01 degrees: 5,200 copies, 1 s; at 0.001: 11 s;
/// at 1e-6 the walk's list outgrew memory).
inline constexpr double kMaxRayCopies = 10000;

/// How a pass's rays are answered: each traced through the Embree scene, or all at once by
/// drawing the stand's triangles over the cells (light/raster.hpp; the same rays and, up to rays
/// that graze an edge, the same hits). `automatic` draws every pass on a GPU
/// (LightConfig::device; a pass of 10,000 plants takes a few milliseconds there, the Embree scene
/// 1.2 s to build on 16 cores) and traces on the host, where drawing costs about what tracing
/// does (1,000 plants on 2 cores, each plant to 0.005: 22.1 s drawing passes of 1.2 M rays and
/// up, 22 s tracing; bench_light --caster).
enum class Caster { automatic, trace, raster };

/// "auto", "trace" or "raster"; throws std::invalid_argument naming --caster otherwise.
Caster parse_caster(const std::string& name);
const char* caster_name(Caster c);

struct LightConfig {
  std::vector<Beam> suns;
  SkyModel sky = SkyModel::soc;
  int sky_directions = 46;  // 0: no diffuse light and no STAR
  Box2d tile;               // relative to stand_origin
  bool periodic = true;
  double error = 0.002;               // standard error asked of the stand's fractions
  std::optional<double> plant_error;  // and of each plant's (root mean square over plants)
  std::optional<double> rays_per_m2;  // instead of the errors: rays per m2 of ground sampled
  double layer_m = 0.1;               // height of the profile's layers
  std::uint64_t seed = 1;
  int pilot_rays = 4096;      // rays of the first pass that sizes each beam's count
  int sky_pilot_rays = 1024;  // per sky direction
  Caster caster = Caster::automatic;
  /// Where given, draws the rasterized passes (a GPU); else the host's threads do.
  RasterDevice* device = nullptr;
};
/// Throws std::invalid_argument naming the option on a value out of range.
void check_config(const LightConfig& c);

struct Estimate {
  double value = 0, se = 0;
};

/// What one direction's rays (or the sky's, combined) found.
struct DirectionLight {
  double elevation_deg = 90, azimuth_deg = 0, weight = 1;
  std::uint64_t rays = 0;
  Estimate fraction;            // of the light on the tile
  Estimate star;                // leaflet silhouette over leaflet area
  std::vector<Estimate> plant;  // of the light on each plant's ground share
  std::vector<Estimate> plant_star;
  std::array<Estimate, kKinds> kind{};  // of the light on the tile, by the kind hit
  std::vector<Estimate> layer;          // of the light on the tile, by the layer hit
};

struct LightResult {
  Box2d tile;
  bool periodic = true;
  SkyModel sky = SkyModel::soc;
  double leaf_area = 0, lai = 0;  // leaflets, one-sided; lai over the tile
  std::vector<double> plant_leaf_area;
  double layer_m = 0.1;
  std::vector<double> layer_leaf_area;  // leaflet area by height layer (triangle centroids)
  LeafAngles leaf_angles;
  DirectionLight ground;               // from the zenith: ground cover
  std::vector<DirectionLight> direct;  // one per sun
  std::vector<DirectionLight> sky_directions;
  std::optional<DirectionLight> diffuse;  // the sky's directions combined with their weights
  std::size_t organs_skipped = 0;         // flattened solids, not in the scene
  std::uint64_t rays = 0;                 // every ray traced, first passes included
  std::uint64_t raster_rays = 0;          // of them, answered by rasterizing
  std::size_t raster_passes = 0;
  std::string raster_device;  // what drew them ("host" or the device's name)
  double scene_s = 0, trace_s = 0, raster_s = 0;
};

/// Computes the light of `stand` as asked. Throws std::invalid_argument on a bad request and
/// std::runtime_error when Embree fails.
LightResult compute_light(const Stand& stand, PrototypeLibrary& lib, const LightConfig& config);

}  // namespace canopy::light
