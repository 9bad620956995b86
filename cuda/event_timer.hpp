#pragma once
/// Kernel time from CUDA events: `start` before launches, `stop` after them; `seconds` sums every
/// start-stop interval (the device's own clock, not the host's).
#include "cuda/check.hpp"

namespace canopy::cuda {

class EventTimer {
 public:
  EventTimer() {
    CANOPY_CUDA_CHECK(cudaEventCreate(&a_));
    CANOPY_CUDA_CHECK(cudaEventCreate(&b_));
  }
  ~EventTimer() {
    cudaEventDestroy(a_);
    cudaEventDestroy(b_);
  }
  EventTimer(const EventTimer&) = delete;
  EventTimer& operator=(const EventTimer&) = delete;
  void start() { CANOPY_CUDA_CHECK(cudaEventRecord(a_)); }
  void stop() {
    CANOPY_CUDA_CHECK(cudaEventRecord(b_));
    CANOPY_CUDA_CHECK(cudaEventSynchronize(b_));
    float ms = 0;
    CANOPY_CUDA_CHECK(cudaEventElapsedTime(&ms, a_, b_));
    seconds_ += ms / 1000.0;
  }
  double seconds() const { return seconds_; }

 private:
  cudaEvent_t a_{}, b_{};
  double seconds_ = 0;
};

}  // namespace canopy::cuda
