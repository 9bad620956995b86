#include "tools/light_device.hpp"

#include "tools/detect_options.hpp"
#include "tools/heap_pages.hpp"

#ifdef CANOPY_HAVE_CUDA
#include "cuda/device.hpp"
#include "cuda/light_raster.hpp"
#endif

#include <fmt/format.h>

#include <stdexcept>

namespace canopy::cli {

std::unique_ptr<light::RasterDevice> make_light_device(const std::string& backend, std::string& note) {
  check_backend_name(backend);
  if (backend == "cpu") {
    note = "host (asked for)";
    return nullptr;
  }
  std::string why = "no GPU device files";
#ifdef CANOPY_HAVE_CUDA
  if (backend == "cuda" || gpu_device_files()) {
    const auto report = cuda::query_devices();
    why = report.unavailable_reason;
    if (!report.devices.empty()) try {
        auto d = std::make_unique<cuda::LightRaster>(0);
        note = fmt::format("{} ({})", d->name(), backend == "cuda" ? "asked for" : "auto: a GPU is present");
        return d;
      } catch (const std::exception& e) {
        why = e.what();
      }
  }
#else
  why = "this build has no CUDA backend";
#endif
  if (backend == "cuda")
    throw std::runtime_error(fmt::format("--backend cuda: no usable GPU ({}); use --backend cpu", why));
  note = fmt::format("host (auto: {})", why);
  return nullptr;
}

}  // namespace canopy::cli
