#pragma once
/// The GPU's drawing and counting of light's cells (light/raster_device.hpp): every organ's
/// triangles projected along the direction and kept per cell by an atomic maximum of their keys,
/// then every pair of neighbouring cells counted, with the host's functions (light/raster.hpp,
/// light/tally.hpp), so the same keys and counts bit for bit. Only the counters come back.
#include "light/raster_device.hpp"

#include <memory>
#include <string>

namespace canopy::cuda {

class LightRaster final : public light::RasterDevice {
 public:
  /// On device `device`. Throws CudaError when it cannot be used.
  explicit LightRaster(int device = 0);
  ~LightRaster() override;
  void count(const light::RasterView& v, const light::RasterGrid& g, double layer_m, std::int32_t layers,
             std::uint64_t* counts) override;
  bool fits(std::uint64_t cells) const override;
  std::string name() const override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace canopy::cuda
