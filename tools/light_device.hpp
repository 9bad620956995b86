#pragma once
/// Where light's rasterized passes are drawn (light/raster_device.hpp), chosen as --backend
/// chooses detection's backend: a GPU for `cuda`, and for `auto` where one is usable; the host's
/// threads for `cpu` or without a GPU.
#include "light/raster_device.hpp"

#include <memory>
#include <string>

namespace canopy::cli {

/// The device, or nullptr for the host's threads; `note` says which and why. Throws
/// std::invalid_argument for `cuda` without a usable GPU.
std::unique_ptr<light::RasterDevice> make_light_device(const std::string& backend, std::string& note);

}  // namespace canopy::cli
