#include "cuda/check.hpp"
#include "cuda/device.hpp"

#include <fmt/format.h>

namespace canopy::cuda {

DeviceReport query_devices() {
  DeviceReport r;
  int count = 0;
  const cudaError_t e = cudaGetDeviceCount(&count);
  if (e != cudaSuccess) {
    r.unavailable_reason = fmt::format("{} ({})", cudaGetErrorString(e), cudaGetErrorName(e));
    cudaGetLastError();  // clear the error so later calls start clean
    return r;
  }
  if (count == 0) r.unavailable_reason = "no CUDA device found";
  for (int i = 0; i < count; ++i) {
    cudaDeviceProp p{};
    if (cudaGetDeviceProperties(&p, i) != cudaSuccess) continue;
    r.devices.push_back({i, p.name, p.major, p.minor, p.totalGlobalMem, p.multiProcessorCount});
  }
  return r;
}

int current_device() noexcept {
  int d = -1;
  if (cudaGetDevice(&d) != cudaSuccess) {
    cudaGetLastError();
    return -1;
  }
  return d;
}

void select_device(int device) noexcept {
  if (device < 0 || cudaSetDevice(device) != cudaSuccess) cudaGetLastError();
}

void reset_device(int device) noexcept {
  if (device < 0 || cudaSetDevice(device) != cudaSuccess || cudaDeviceReset() != cudaSuccess)
    cudaGetLastError();
}

}  // namespace canopy::cuda
