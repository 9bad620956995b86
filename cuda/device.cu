// The device self test: a kernel of this build, run and checked on a given device.
#include "cuda/check.hpp"
#include "cuda/device.hpp"

#include <string>
#include <vector>

namespace canopy::cuda {
namespace {

__global__ void iota_squares(int* out, int n) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) out[i] = i * i;
}

}  // namespace

void self_test(int device) {
  CANOPY_CUDA_CHECK(cudaSetDevice(device));
  constexpr int n = 1000;
  int* d = nullptr;
  CANOPY_CUDA_CHECK(cudaMalloc(&d, n * sizeof(int)));
  iota_squares<<<(n + 255) / 256, 256>>>(d, n);
  const cudaError_t launch = cudaGetLastError();
  std::vector<int> h(n);
  const cudaError_t copy = cudaMemcpy(h.data(), d, n * sizeof(int), cudaMemcpyDeviceToHost);
  cudaFree(d);
  check(launch, "iota_squares launch", __FILE__, __LINE__);
  check(copy, "cudaMemcpy", __FILE__, __LINE__);
  for (int i = 0; i < n; ++i)
    if (h[i] != i * i)
      throw CudaError("self test: element " + std::to_string(i) + " is " + std::to_string(h[i]) + ", expected " +
                      std::to_string(i * i));
}

}  // namespace canopy::cuda
