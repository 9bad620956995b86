#pragma once
/// The first exception the threads of a parallel region meet. An exception may not leave an
/// OpenMP region (the program would end in std::terminate): each thread's catch block keeps it
/// here (the first one wins, the others are dropped) and the region's owner throws it once the
/// region is over. Threads may look at caught() to stop early.
#include <atomic>
#include <exception>

namespace canopy {

class FirstException {
 public:
  /// Inside a catch block: keeps the exception being handled unless one is kept already.
  void keep() noexcept {
    if (!caught_.exchange(true)) kept_ = std::current_exception();
  }
  /// Whether a thread has kept one (relaxed: a hint for the others to stop).
  bool caught() const noexcept { return caught_.load(std::memory_order_relaxed); }
  /// After the region (its end orders the keeping thread's write before this read): throws the
  /// kept exception, if any.
  void rethrow() const {
    if (kept_) std::rethrow_exception(kept_);
  }

 private:
  std::exception_ptr kept_;
  std::atomic<bool> caught_{false};
};

}  // namespace canopy
