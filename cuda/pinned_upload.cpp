#include "cuda/pinned_upload.hpp"

#include "cuda/check.hpp"

#include <omp.h>

#include <algorithm>
#include <cstring>

namespace canopy::cuda {

PinnedUpload::~PinnedUpload() {
  if (stream_) cudaStreamSynchronize(stream_), cudaStreamDestroy(stream_);
  for (int i = 0; i < 2; ++i) {
    if (done_[i]) cudaEventDestroy(done_[i]);
    if (host_[i]) cudaFreeHost(host_[i]);
  }
}

void PinnedUpload::allocate() {
  CANOPY_CUDA_CHECK(cudaStreamCreate(&stream_));  // blocking: ordered with the default stream
  for (int i = 0; i < 2; ++i) {
    CANOPY_CUDA_CHECK(cudaHostAlloc(&host_[i], block_, cudaHostAllocDefault));
    CANOPY_CUDA_CHECK(cudaEventCreateWithFlags(&done_[i], cudaEventDisableTiming));
    CANOPY_CUDA_CHECK(cudaEventRecord(done_[i], stream_));
  }
}

void PinnedUpload::copy(void* dst, const void* src, std::size_t bytes) {
  if (bytes < block_) {
    if (bytes) CANOPY_CUDA_CHECK(cudaMemcpy(dst, src, bytes, cudaMemcpyHostToDevice));
    return;
  }
  if (!stream_) allocate();
  const char* from = static_cast<const char*>(src);
  char* to = static_cast<char*>(dst);
  for (std::size_t at = 0; at < bytes; at += block_) {
    const std::size_t n = std::min(block_, bytes - at);
    const int b = next_;
    next_ ^= 1;
    CANOPY_CUDA_CHECK(cudaEventSynchronize(done_[b]));  // the block's last copy has left it
    char* stage = static_cast<char*>(host_[b]);
    // Slices of at least 256 KiB per thread: a block of 8 MiB on up to 32 threads.
    const std::size_t slice = std::max<std::size_t>(std::size_t(256) << 10, (n + 31) / 32);
    const auto slices = static_cast<std::ptrdiff_t>((n + slice - 1) / slice);
#pragma omp parallel for schedule(static) if (slices > 1)
    for (std::ptrdiff_t k = 0; k < slices; ++k) {
      const std::size_t lo = static_cast<std::size_t>(k) * slice, len = std::min(slice, n - lo);
      std::memcpy(stage + lo, from + at + lo, len);
    }
    CANOPY_CUDA_CHECK(cudaMemcpyAsync(to + at, stage, n, cudaMemcpyHostToDevice, stream_));
    CANOPY_CUDA_CHECK(cudaEventRecord(done_[b], stream_));
  }
}

void PinnedUpload::finish() {
  if (stream_) CANOPY_CUDA_CHECK(cudaStreamSynchronize(stream_));
}

}  // namespace canopy::cuda
