#pragma once
/// The one CUDA check: every runtime call and launch goes through it and throws with context.
/// Kept free of fmt so that nvcc-compiled files can include it.
#include "collision/backend_failure.hpp"

#include <cuda_runtime.h>

#include <stdexcept>
#include <string>

namespace canopy::cuda {

/// A failure of the device (BackendFailure: `--backend auto` goes on with the CPU).
class CudaError : public BackendFailure {
 public:
  using BackendFailure::BackendFailure;
};

/// Throws CudaError naming the call, the place and the runtime's message.
[[noreturn]] void throw_cuda_error(cudaError_t e, const char* what, const char* file, int line);

inline void check(cudaError_t e, const char* what, const char* file, int line) {
  if (e != cudaSuccess) throw_cuda_error(e, what, file, line);
}

}  // namespace canopy::cuda

#define CANOPY_CUDA_CHECK(call) ::canopy::cuda::check((call), #call, __FILE__, __LINE__)
/// After a kernel launch: checks that the launch itself was accepted.
#define CANOPY_CUDA_CHECK_LAUNCH(what) ::canopy::cuda::check(cudaGetLastError(), what, __FILE__, __LINE__)
