#include "cuda/pinned_upload.hpp"

#include "cuda/check.hpp"

#include <algorithm>
#include <cstring>
#include <exception>
#include <thread>
#include <utility>

namespace canopy::cuda {

namespace {

void free_worker(PinnedUpload::Worker& w) noexcept {
  if (w.stream) cudaStreamSynchronize(w.stream), cudaStreamDestroy(w.stream);
  for (int i = 0; i < 2; ++i) {
    if (w.done[i]) cudaEventDestroy(w.done[i]);
    if (w.host[i]) cudaFreeHost(w.host[i]);
  }
  w = {};
}

}  // namespace

PinnedUpload::~PinnedUpload() {
  if (reserving_.joinable()) reserving_.join();
  drop();  // copies under way end before their blocks go
  for (Worker& w : workers_) free_worker(w);
}

void PinnedUpload::allocate() {
  // Made aside and kept only whole: a failure partway (pinned memory refused) leaves none, so a
  // later load tries again instead of copying through a missing block.
  std::vector<Worker> made(kWorkers);
  try {
    CANOPY_CUDA_CHECK(cudaGetDevice(&device_));
    for (Worker& w : made) {
      CANOPY_CUDA_CHECK(cudaStreamCreateWithFlags(&w.stream, cudaStreamNonBlocking));
      for (int i = 0; i < 2; ++i) {
        CANOPY_CUDA_CHECK(cudaHostAlloc(&w.host[i], kBlock, cudaHostAllocDefault));
        CANOPY_CUDA_CHECK(cudaEventCreateWithFlags(&w.done[i], cudaEventDisableTiming));
        CANOPY_CUDA_CHECK(cudaEventRecord(w.done[i], w.stream));
      }
    }
  } catch (...) {
    for (Worker& w : made) free_worker(w);
    throw;
  }
  workers_ = std::move(made);
}

void PinnedUpload::copy(void* dst, const void* src, std::size_t bytes) {
  if (bytes) jobs_.push_back({static_cast<char*>(dst), static_cast<const char*>(src), bytes});
}

void PinnedUpload::run(Worker& w, std::size_t lo, std::size_t hi) const {
  CANOPY_CUDA_CHECK(cudaSetDevice(device_));  // a thread's current device is its own
  int next = 0;
  std::size_t at = 0;  // the queued bytes before job j
  for (const Job& j : jobs_) {
    const std::size_t from = std::max(lo, at), to = std::min(hi, at + j.bytes);
    for (std::size_t k = from; k < to; k += kBlock) {
      const std::size_t n = std::min(kBlock, to - k);
      const int b = next;
      next ^= 1;
      CANOPY_CUDA_CHECK(cudaEventSynchronize(w.done[b]));  // the block's last copy has left it
      std::memcpy(w.host[b], j.src + (k - at), n);
      CANOPY_CUDA_CHECK(cudaMemcpyAsync(j.dst + (k - at), w.host[b], n, cudaMemcpyHostToDevice, w.stream));
      CANOPY_CUDA_CHECK(cudaEventRecord(w.done[b], w.stream));
    }
    at += j.bytes;
  }
  CANOPY_CUDA_CHECK(cudaStreamSynchronize(w.stream));
}

void PinnedUpload::reserve() {
  if (reserving_.joinable()) {
    reserving_.join();
    if (reserve_failed_) std::rethrow_exception(std::exchange(reserve_failed_, nullptr));
  }
  if (workers_.empty()) allocate();
}

void PinnedUpload::reserve_in_background() {
  if (!workers_.empty() || reserving_.joinable()) return;
  int device = 0;
  CANOPY_CUDA_CHECK(cudaGetDevice(&device));
  reserving_ = std::jthread([this, device] {
    try {
      CANOPY_CUDA_CHECK(cudaSetDevice(device));  // a thread's current device is its own
      allocate();
    } catch (...) {
      reserve_failed_ = std::current_exception();
    }
  });
}

void PinnedUpload::start() {
  std::size_t total = 0;
  for (const Job& j : jobs_) total += j.bytes;
  if (total < kStagedFrom) {
    for (const Job& j : jobs_) CANOPY_CUDA_CHECK(cudaMemcpy(j.dst, j.src, j.bytes, cudaMemcpyHostToDevice));
    jobs_.clear();
    return;
  }
  reserve();
  // A load replaces what kernels of any stream may still read: they finish first.
  CANOPY_CUDA_CHECK(cudaDeviceSynchronize());
  const auto share = [&](std::size_t w) { return total * w / workers_.size(); };
  failed_.assign(workers_.size(), nullptr);
  for (std::size_t w = 0; w < workers_.size(); ++w)
    threads_.emplace_back([this, w, lo = share(w), hi = share(w + 1)] {
      try {
        run(workers_[w], lo, hi);
      } catch (...) {
        failed_[w] = std::current_exception();
      }
    });
}

void PinnedUpload::drop() noexcept {
  threads_.clear();  // joined
  jobs_.clear();
  failed_.clear();
}

void PinnedUpload::wait() {
  threads_.clear();  // joined
  jobs_.clear();
  std::vector<std::exception_ptr> failed = std::exchange(failed_, {});
  for (const auto& e : failed)
    if (e) std::rethrow_exception(e);
}

}  // namespace canopy::cuda
