#pragma once
/// Memory a finished resolution hands over to be let go on a thread of its own: at 10,000 plants
/// its candidate pools hold hundreds of thousands of lists, whose freeing is a noticeable share
/// of a GPU resolution (bench_resolve: about 6 %), after every turn was made. The caller goes on
/// (exporting, detecting again) while they go. One such thread at a time per process: a new
/// hand-over first waits for the last one, and so does the process's exit.
#include <functional>
#include <mutex>
#include <thread>

namespace canopy {

class BackgroundRelease {
 public:
  /// The process's one.
  static BackgroundRelease& instance();
  /// Runs `release` (which owns what it frees) on the release thread.
  void hand_over(std::function<void()> release);
  /// Waits until what was handed over is gone.
  void wait();
  ~BackgroundRelease();

 private:
  BackgroundRelease() = default;
  std::mutex mutex_;
  std::thread thread_;
};

}  // namespace canopy
