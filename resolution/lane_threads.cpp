#include "resolution/lane_threads.hpp"

#include <algorithm>

namespace canopy {

LaneThreads::LaneThreads(std::size_t lanes) : failed_(lanes > 0 ? lanes : 1) {
  for (std::size_t l = 1; l < lanes; ++l) threads_.emplace_back([this, l] { serve(l); });
}

LaneThreads::~LaneThreads() {
  {
    const std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : threads_) t.join();
}

void LaneThreads::serve(std::size_t lane) {
  std::uint64_t seen = 0;
  for (;;) {
    const std::function<void(std::size_t)>* job = nullptr;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
      job = job_;
    }
    std::exception_ptr failed;
    try {
      (*job)(lane);
    } catch (...) {
      failed = std::current_exception();
    }
    const std::lock_guard lock(mutex_);
    failed_[lane] = failed;
    if (--busy_ == 0) done_.notify_all();
  }
}

void LaneThreads::run(const std::function<void(std::size_t)>& job) {
  {
    const std::lock_guard lock(mutex_);
    job_ = &job;
    busy_ = threads_.size();
    std::fill(failed_.begin(), failed_.end(), nullptr);
    ++generation_;
  }
  wake_.notify_all();
  std::exception_ptr mine;
  try {
    job(0);
  } catch (...) {
    mine = std::current_exception();
  }
  std::unique_lock lock(mutex_);
  done_.wait(lock, [&] { return busy_ == 0; });
  if (mine) std::rethrow_exception(mine);
  for (const std::exception_ptr& e : failed_)
    if (e) std::rethrow_exception(e);
}

}  // namespace canopy
