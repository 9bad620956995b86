// The device self test: a kernel of this build, run and checked on a given device.
#include "cuda/check.hpp"
#include "cuda/device.hpp"
#include "cuda/device_buffer.hpp"
#include "geometry/triangle_distance.hpp"

#include <string>
#include <vector>

namespace canopy::cuda {
namespace {

__global__ void iota_squares(int* out, int n) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) out[i] = i * i;
}

/// vertices: six per pair, a's three then b's.
__global__ void triangle_tests_kernel(const Vec3f* vertices, std::uint32_t n, float clearance,
                                      std::uint8_t* out) {
  const std::uint32_t k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= n) return;
  const Vec3f* p = vertices + 6 * std::size_t{k};
  const Vec3f a[3] = {p[0], p[1], p[2]}, b[3] = {p[3], p[4], p[5]};
  out[k] = (clearance > 0 ? triangles_within(a, b, clearance) : triangles_intersect(a, b)) ? 1 : 0;
}

}  // namespace

std::vector<std::uint8_t> device_triangle_tests(const std::vector<std::array<Vec3f, 6>>& pairs,
                                                float clearance) {
  std::vector<Vec3f> flat;
  for (const auto& pair : pairs) flat.insert(flat.end(), pair.begin(), pair.end());
  DeviceBuffer<Vec3f> in;
  DeviceBuffer<std::uint8_t> out(pairs.size());
  in.upload(flat);
  const auto n = static_cast<std::uint32_t>(pairs.size());
  if (n) triangle_tests_kernel<<<(n + 127) / 128, 128>>>(in.get(), n, clearance, out.get());
  CANOPY_CUDA_CHECK_LAUNCH("triangle_tests_kernel");
  return out.download(pairs.size());
}

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
      throw CudaError("self test: element " + std::to_string(i) + " is " + std::to_string(h[i]) +
                      ", expected " + std::to_string(i * i));
}

}  // namespace canopy::cuda
