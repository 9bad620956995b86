#include "resolution/background_release.hpp"

namespace canopy {

BackgroundRelease& BackgroundRelease::instance() {
  static BackgroundRelease one;
  return one;
}

void BackgroundRelease::hand_over(std::function<void()> release) {
  const std::lock_guard lock(mutex_);
  if (thread_.joinable()) thread_.join();
  thread_ = std::thread(std::move(release));
}

void BackgroundRelease::wait() {
  const std::lock_guard lock(mutex_);
  if (thread_.joinable()) thread_.join();
}

BackgroundRelease::~BackgroundRelease() { wait(); }

}  // namespace canopy
