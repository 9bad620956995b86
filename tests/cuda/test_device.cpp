// The CUDA backend on a real device; reports itself as skipped (exit 77) where there is no GPU.
#include "cuda/device.hpp"

#include <doctest/doctest.h>

#include <cstdio>
#include <cstdlib>

namespace {
// Runs before doctest's main: with no device, say so and exit with ctest's skip code.
const bool skip_without_gpu = [] {
  const auto report = canopy::cuda::query_devices();
  if (report.devices.empty()) {
    std::printf("SKIPPED: no CUDA device: %s\n", report.unavailable_reason.c_str());
    std::exit(77);
  }
  return true;
}();
}  // namespace

TEST_CASE("every CUDA device runs this build's kernels") {
  const auto report = canopy::cuda::query_devices();
  REQUIRE_FALSE(report.devices.empty());
  for (const auto& d : report.devices) {
    INFO(d.name);
    CHECK(d.major >= 9);  // built for sm_90 with compute_90 PTX
    CHECK_NOTHROW(canopy::cuda::self_test(d.index));
  }
}
