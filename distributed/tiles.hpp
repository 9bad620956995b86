#pragma once
/// Spatial tiles of a stand for several processes (docs/design.md "Data flow", split across ranks): the
/// field is cut into strips along its longer horizontal extent, balanced by plant count (not by
/// area); each tile owns its plants and also holds, as a halo, every plant within `halo` metres
/// of its strip, so that what its own plants may touch (and what decides their turns) is always
/// on hand. No MPI here: the tiling is a pure function of the placements, the same on every rank.
#include "geometry/layout.hpp"

#include <cstdint>
#include <vector>

namespace canopy {

struct Tiling {
  int axis = 0;                // 0: strips across x, 1: across y
  std::vector<int> owner;      // per plant (global id): the tile that owns it
  std::vector<double> lo, hi;  // per tile: its owned plants' smallest and largest coordinate
  std::vector<std::size_t> owned_count;

  double coordinate(const PlantPlacement& p) const { return axis == 0 ? p.x : p.y; }
};

/// `tiles` strips of (as nearly as can be) equal plant counts; plants on the same coordinate
/// are ordered by id, so a plant exactly on a border belongs to exactly one tile. A tile may be
/// empty (more tiles than plants).
Tiling make_tiling(const std::vector<PlantPlacement>& plants, int tiles);

/// The plants tile `t` holds, ascending by id: its own and those of other tiles whose coordinate
/// lies within `halo` metres of its strip.
std::vector<std::uint32_t> tile_region(const Tiling& tiling, const std::vector<PlantPlacement>& plants, int t,
                                       double halo);

/// The tiles (other than the owner) whose region holds plant `p`.
std::vector<int> tiles_holding(const Tiling& tiling, const std::vector<PlantPlacement>& plants, std::size_t p,
                               double halo);

}  // namespace canopy
