#pragma once
/// A run's thread count over all its phases. Detection, resolution and growing take their count
/// as an argument and pass it to their parallel regions; the rest (building the tree, the plant
/// grid, export) run on OpenMP's default team, which this bounds for the calling thread while it
/// lives: `--threads N` means N threads throughout, not only where a phase was told.
namespace canopy {

class ThreadLimit {
 public:
  /// threads <= 0: no limit (OpenMP's default, all cores unless OMP_NUM_THREADS says otherwise).
  explicit ThreadLimit(int threads);
  ~ThreadLimit();
  ThreadLimit(const ThreadLimit&) = delete;
  ThreadLimit& operator=(const ThreadLimit&) = delete;

 private:
  int before_ = 0;
  bool set_ = false;
};

}  // namespace canopy
