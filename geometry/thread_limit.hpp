#pragma once
/// A run's thread count over all its phases. Detection, resolution and growing take their count
/// as an argument and pass it to their parallel regions; the rest (building the tree, the plant
/// grid, export) run on OpenMP's default team, which this bounds for the calling thread while it
/// lives: `--threads N` means N threads throughout, not only where a phase was told.
namespace canopy {

/// The most threads a run may use: 1024, or the machine's processor count where that is more.
/// libgomp starts a team with its bookkeeping on the caller's stack and stops the process when a
/// thread cannot be made, so a count in the tens of thousands (typed by mistake, or from
/// OMP_NUM_THREADS) crashed instead of being refused.
int max_threads();

/// The thread count `threads` stands for (0: OpenMP's default, OMP_NUM_THREADS or the cores).
/// Throws std::invalid_argument for a negative count, and naming OMP_NUM_THREADS or the count
/// when it is more than max_threads().
int checked_threads(int threads);

class ThreadLimit {
 public:
  /// threads <= 0: no limit (OpenMP's default, all cores unless OMP_NUM_THREADS says otherwise).
  /// Throws as checked_threads does, before anything is changed.
  explicit ThreadLimit(int threads);
  ~ThreadLimit();
  ThreadLimit(const ThreadLimit&) = delete;
  ThreadLimit& operator=(const ThreadLimit&) = delete;

 private:
  int before_ = 0;
  bool set_ = false;
};

}  // namespace canopy
