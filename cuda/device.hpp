#pragma once
/// Which CUDA devices this process can use, without throwing when there are none.
#include <string>
#include <vector>

namespace canopy::cuda {

struct DeviceInfo {
  int index = 0;
  std::string name;
  int major = 0, minor = 0;
  std::size_t memory_bytes = 0;
  int multiprocessors = 0;
};

struct DeviceReport {
  std::vector<DeviceInfo> devices;
  std::string unavailable_reason;  // why there are none (no driver, no device, ...)
};

/// Lists the devices; never throws: a missing driver or device is a reason, not an error.
DeviceReport query_devices();

/// Runs a small kernel built from this project's code on `device` and checks its result, proving
/// the binary's sm_90 / PTX code loads and runs there. Throws CudaError on failure.
void self_test(int device);

}  // namespace canopy::cuda
