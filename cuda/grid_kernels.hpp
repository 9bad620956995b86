#pragma once
/// The plant level on the device: a uniform grid over plant origins (cells at least twice the
/// largest plant radius, so every pair whose bounds meet lies in neighbouring cells), plants
/// sorted by cell, and one thread per plant looking through the 3 x 3 cells around it. The
/// pairs are those of the host's plant_level (the same bound test, plant_bounds_meet), as keys.
#include "cuda/detect_kernels.hpp"

#include <cstdint>

namespace canopy::cuda {

struct GridView {
  const PlantBound* plants;
  const PlantOrigin* origins;
  const std::uint64_t* cells;    // cell keys, sorted
  const std::uint32_t* members;  // plant ids in the order of `cells`
  std::uint32_t n;               // plants
  double x0, y0, cell;           // grid corner (the least origin coordinates) and cell size
  const std::uint8_t* self;      // per plant: it holds a free pair, so it meets itself
  const std::uint8_t* active;    // per plant, or null for all: pairs need an active plant
};

/// keys[p] = the cell of plant p, ids[p] = p.
void launch_plant_cells(const PlantOrigin* origins, std::uint32_t n, double x0, double y0, double cell,
                        std::uint64_t* keys, std::uint32_t* ids);
/// Plant pairs pair_key(p, q): p < q with meeting bounds (counted `between`), and (p, p) for the
/// plants that meet themselves (counted `within`).
void launch_plant_pairs(const GridView& g, std::uint64_t* out, unsigned long long capacity,
                        Counters* counters);

}  // namespace canopy::cuda
