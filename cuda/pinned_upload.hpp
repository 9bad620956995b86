#pragma once
/// Host-to-device copies of a load's large arrays through pinned staging blocks, on a few
/// threads of their own: each thread takes a contiguous share of the bytes and copies it,
/// a block at a time, into one of its two pinned blocks while the device takes the other. A
/// plain cudaMemcpy from pageable memory goes through the driver's staging on one thread
/// (the 10,000-plant stand's 200 MB in 45-59 ms on the H100 machine; staged 19-24 ms, and
/// 34-43 ms for the first load, which allocates the blocks: bench_stand, each load timed).
/// The threads are std::threads, not an OpenMP team: after resolution, whose lanes run teams of
/// their own, an OpenMP team copying the same blocks took 0.33 s instead of 0.02.
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

#include <cuda_runtime.h>

namespace canopy::cuda {

class PinnedUpload {
 public:
  PinnedUpload() = default;
  PinnedUpload(const PinnedUpload&) = delete;
  PinnedUpload& operator=(const PinnedUpload&) = delete;
  ~PinnedUpload();
  /// Queues `bytes` from host `src` to device `dst` (both must stay as they are until finish()).
  void copy(void* dst, const void* src, std::size_t bytes);
  /// Makes the queued copies and waits for them. Loads below kStagedFrom bytes in all go
  /// through cudaMemcpy; the blocks are allocated at the first larger load (or by reserve())
  /// and kept.
  void finish() {
    start();
    wait();
  }
  /// The same in two halves: start() sets the copies going on the staging threads and returns
  /// (the host is free for other work meanwhile; nothing may be queued until wait()), wait()
  /// waits for them and throws what failed. A small load is copied by start() itself.
  void start();
  void wait();
  /// Waits for copies under way and forgets them and what failed in them: a load that an
  /// exception abandoned between start() and wait(), before anything is queued again.
  void drop() noexcept;
  /// Allocates the staging blocks now, if not yet (waiting for reserve_in_background's).
  void reserve();
  /// Starts allocating them on a thread of its own, on the calling thread's device, and returns:
  /// a backend that starts while the stand grows has them by its first large load (the
  /// allocation, 10-14 ms on the H100 machine, may hold up a small stand's first copies instead).
  void reserve_in_background();

  static constexpr std::size_t kBlock = std::size_t(4) << 20;
  static constexpr std::size_t kStagedFrom = std::size_t(64) << 20;
  static constexpr int kWorkers = 4;

  /// One staging thread's two pinned blocks, their events and its stream.
  struct Worker {
    void* host[2] = {nullptr, nullptr};
    cudaEvent_t done[2] = {nullptr, nullptr};
    cudaStream_t stream = nullptr;
  };

 private:
  struct Job {
    char* dst;
    const char* src;
    std::size_t bytes;
  };
  void allocate();
  /// Worker w's share [lo, hi) of the queued bytes, taken in order.
  void run(Worker& w, std::size_t lo, std::size_t hi) const;

  std::vector<Job> jobs_;
  std::vector<Worker> workers_;
  std::vector<std::jthread> threads_;       // the copies under way, one per worker
  std::vector<std::exception_ptr> failed_;  // beside workers_
  std::jthread reserving_;                  // reserve_in_background's
  std::exception_ptr reserve_failed_;
  int device_ = -1;
};

}  // namespace canopy::cuda
