#pragma once
/// Which CUDA devices this process can use, without throwing when there are none; a self test;
/// the shared triangle predicates run on the device for the tests.
#include "geometry/vec.hpp"

#include <array>
#include <cstdint>
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

/// The calling thread's current device (the one a backend made current on it); -1 where there
/// is none.
int current_device() noexcept;

/// Makes `device` the calling thread's current device; errors are ignored.
void select_device(int device) noexcept;

/// Ends this process's use of `device`: its context and everything in it destroyed
/// (cudaDeviceReset), for a process that will not use the device again; errors are ignored.
void reset_device(int device) noexcept;

/// The shared triangle predicates (geometry/triangle_test.hpp and triangle_distance.hpp) run on
/// the current device: for each pair (a's three vertices, then b's), whether the triangles meet,
/// or with a positive `clearance` whether they lie within it. Lets the tests hold the device's
/// answers to the host's.
std::vector<std::uint8_t> device_triangle_tests(const std::vector<std::array<Vec3f, 6>>& pairs,
                                                float clearance);

}  // namespace canopy::cuda
