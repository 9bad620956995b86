#pragma once
/// Threads that plan batches of contacts beside the caller's (resolution/plan_round.hpp), kept
/// for a whole resolution: each keeps its OpenMP team (the threads of a team are made when its
/// first parallel region starts) and its candidates' memory from pass to pass and round to
/// round (resolution then hands that memory to resolution/background_release.hpp). Made afresh
/// for every pass, lanes cost a GPU resolution much of its time (bench_resolve at 1,000 plants:
/// about a third).
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace canopy {

class LaneThreads {
 public:
  /// `lanes` - 1 threads of its own (lane 0 is the caller's).
  explicit LaneThreads(std::size_t lanes);
  LaneThreads(const LaneThreads&) = delete;
  LaneThreads& operator=(const LaneThreads&) = delete;
  ~LaneThreads();
  std::size_t lanes() const { return threads_.size() + 1; }
  /// job(l) for every lane l, lane 0 on the calling thread; returns when all are done and
  /// rethrows the first lane's exception, if any.
  void run(const std::function<void(std::size_t)>& job);

 private:
  void serve(std::size_t lane);

  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  const std::function<void(std::size_t)>* job_ = nullptr;
  std::uint64_t generation_ = 0;  // counts the jobs given
  std::size_t busy_ = 0;          // lanes of the current job not done yet
  bool stop_ = false;
  std::vector<std::exception_ptr> failed_;  // per lane, for the current job
};

}  // namespace canopy
