#pragma once
/// A device that draws the rasterizer's cells and counts them (cuda/light_raster.hpp on a GPU):
/// the same keys, bit for bit, as the host's rasterize() (light/raster_stand.hpp) and the same
/// counts, from the same functions (light/raster.hpp, light/tally.hpp). light/ declares it and the CUDA
/// folder implements it, so light never depends on CUDA.
#include "light/raster.hpp"

#include <cstdint>
#include <string>

namespace canopy::light {

class RasterDevice {
 public:
  virtual ~RasterDevice() = default;
  /// Draws the stand `v` over `g` and counts its cells' answers as tally_cells does (light/
  /// raster_stand.hpp): `counts` (host memory, tally_slots(v.plants, layers) numbers) gets the
  /// counters in tally_slot's order. A run draws one stand many times: what the device uploads
  /// for `v` is kept for the next call with the same `v.generation`. Throws std::runtime_error
  /// when the device fails.
  virtual void count(const RasterView& v, const RasterGrid& g, double layer_m, std::int32_t layers,
                     std::uint64_t* counts) = 0;
  /// Whether the cells of a pass of `cells` rays fit in the device's free memory.
  virtual bool fits(std::uint64_t cells) const = 0;
  /// The device, in words (for light.json).
  virtual std::string name() const = 0;
};

}  // namespace canopy::light
