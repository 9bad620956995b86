#pragma once
/// The rays of one direction: a jittered grid over a ground region, one ray per cell, each cell's
/// point drawn from a hash of (seed, direction, cell), so every ray and every count is the same
/// on any thread count. A ray starts above the stand, travels toward the ground point of its
/// cell, and ends on the ground (z = 0).
#include "geometry/stand.hpp"
#include "light/scene.hpp"
#include "light/tally.hpp"

#include <cstdint>
#include <vector>

namespace canopy::light {

/// What a hit organ counts as: its plant, kind, whether it is a leaflet.
struct OrganIndex {
  std::vector<std::int32_t> plant;
  std::vector<std::uint8_t> kind;
  explicit OrganIndex(const Stand& s);
};

struct Grid {
  Box2d region;                  // ground region sampled (relative to stand_origin)
  std::uint64_t nx = 2, ny = 1;  // nx even: cells (2k, j) and (2k + 1, j) are a pair
  std::uint64_t rays() const { return nx * ny; }
};
/// About `rays` cells (at least 2) over `region`, about square.
Grid make_grid(const Box2d& region, double rays);

struct DirectionJob {
  Vec3d toward;  // unit vector toward the source (z > 0)
  Grid grid;
  std::uint64_t seed = 1;
  std::uint64_t stream = 0;  // the direction's own stream of cell points
  double layer_m = 0.1;      // height layers of the profile
  std::size_t layers = 1;
  bool periodic = true;  // the grid covers the tile, which repeats (for the rasterizer)
};

/// Traces every ray of the job and counts what they hit (OpenMP threads over grid rows).
Tally trace_direction(const Scene& scene, const OrganIndex& organs, std::size_t plants,
                      const DirectionJob& job);

}  // namespace canopy::light
