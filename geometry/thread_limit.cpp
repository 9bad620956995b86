#include "geometry/thread_limit.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <stdexcept>

namespace canopy {

int max_threads() { return std::max(1024, omp_get_num_procs()); }

int checked_threads(int threads) {
  if (threads < 0)
    throw std::invalid_argument(
        fmt::format("the thread count must be at least 0 (0: all cores; got {})", threads));
  const int most = max_threads();
  if (threads > most)
    throw std::invalid_argument(
        fmt::format("the thread count {} is more than the {} canopy runs at most", threads, most));
  if (threads > 0) return threads;
  const int fallback = omp_get_max_threads();
  if (fallback > most)
    throw std::invalid_argument(
        fmt::format("OMP_NUM_THREADS asks for {} threads, more than the {} canopy runs at most; set it lower "
                    "or give a thread count",
                    fallback, most));
  return fallback;
}

ThreadLimit::ThreadLimit(int threads) : before_(omp_get_max_threads()), set_(threads > 0) {
  checked_threads(threads);
  if (set_) omp_set_num_threads(threads);
}

ThreadLimit::~ThreadLimit() {
  if (set_) omp_set_num_threads(before_);
}

}  // namespace canopy
