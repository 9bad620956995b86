#pragma once
/// When the device had a lane's work in hand (the runner's statistics): a pair of CUDA events per
/// kernel of a call, recorded in the lane's stream before it and after it, read once the work
/// is done. The union of every lane's intervals is the time the device had kernels of
/// some lane queued or running; against the host's wall time it says whether the scan waits
/// for the device or the device for the host.
#include "cuda/check.hpp"

#include <algorithm>
#include <utility>
#include <vector>

namespace canopy::cuda {

class BusyTimeline {
 public:
  BusyTimeline() = default;
  BusyTimeline(const BusyTimeline&) = delete;
  BusyTimeline& operator=(const BusyTimeline&) = delete;
  ~BusyTimeline() { clear(); }
  /// Every event let go: the timeline starts again.
  void clear() {
    for (auto [a, b] : marks_) {
      if (a) cudaEventDestroy(a);
      if (b) cudaEventDestroy(b);
    }
    marks_.clear();
  }
  /// Before a kernel in `stream`.
  void begin(cudaStream_t stream) {
    marks_.emplace_back(nullptr, nullptr);  // each event kept as soon as it is made
    CANOPY_CUDA_CHECK(cudaEventCreate(&marks_.back().first));
    CANOPY_CUDA_CHECK(cudaEventCreate(&marks_.back().second));
    CANOPY_CUDA_CHECK(cudaEventRecord(marks_.back().first, stream));
  }
  /// After that kernel.
  void end(cudaStream_t stream) { CANOPY_CUDA_CHECK(cudaEventRecord(marks_.back().second, stream)); }
  /// Each interval in seconds from `origin` (an event recorded before all of them), appended.
  void intervals(cudaEvent_t origin, std::vector<std::pair<double, double>>& out) const {
    for (auto [a, b] : marks_) {
      float ta = 0, tb = 0;
      CANOPY_CUDA_CHECK(cudaEventElapsedTime(&ta, origin, a));
      CANOPY_CUDA_CHECK(cudaEventElapsedTime(&tb, origin, b));
      out.emplace_back(ta / 1e3, tb / 1e3);
    }
  }
  /// The length of the union of `spans`, and the sum of their lengths.
  static std::pair<double, double> covered(std::vector<std::pair<double, double>> spans) {
    std::sort(spans.begin(), spans.end());
    double total = 0, sum = 0, at = -1e300;
    for (auto [a, b] : spans) {
      sum += b - a;
      if (b <= at) continue;
      total += b - std::max(a, at);
      at = b;
    }
    return {total, sum};
  }

 private:
  std::vector<std::pair<cudaEvent_t, cudaEvent_t>> marks_;
};

}  // namespace canopy::cuda
