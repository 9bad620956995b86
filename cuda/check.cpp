#include "cuda/check.hpp"

#include <fmt/format.h>

namespace canopy::cuda {

void throw_cuda_error(cudaError_t e, const char* what, const char* file, int line) {
  throw CudaError(fmt::format("CUDA error in {} ({}:{}): {} ({})", what, file, line, cudaGetErrorString(e),
                              cudaGetErrorName(e)));
}

}  // namespace canopy::cuda
