#pragma once
/// Host-to-device copies of large arrays through two pinned staging blocks: the host's threads
/// copy one block while the device takes the other, so a copy runs at the bus's speed rather
/// than at what one thread copying pageable memory into the driver's own staging achieves (the
/// stand's first upload, about 200 MB at 10,000 plants, took 61 ms that way on the H200
/// machine: bench_stand's upload_s).
#include <cstddef>

#include <cuda_runtime.h>

namespace canopy::cuda {

class PinnedUpload {
 public:
  /// The blocks are allocated at the first copy (pinned memory is slow to allocate: made once
  /// per owner, kept).
  explicit PinnedUpload(std::size_t block_bytes = std::size_t(8) << 20) : block_(block_bytes) {}
  PinnedUpload(const PinnedUpload&) = delete;
  PinnedUpload& operator=(const PinnedUpload&) = delete;
  ~PinnedUpload();
  /// Copies `bytes` from host `src` to device `dst`; the copy may still be running on return
  /// (finish() waits). Copies below one block go straight through cudaMemcpy.
  void copy(void* dst, const void* src, std::size_t bytes);
  /// Waits for every copy made.
  void finish();
  /// Allocates the blocks now (a backend does it as it starts, while the stand grows).
  void reserve() {
    if (!stream_) allocate();
  }

 private:
  void allocate();
  std::size_t block_;
  void* host_[2] = {nullptr, nullptr};
  cudaEvent_t done_[2] = {nullptr, nullptr};
  cudaStream_t stream_ = nullptr;
  int next_ = 0;
};

}  // namespace canopy::cuda
