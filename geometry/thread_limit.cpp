#include "geometry/thread_limit.hpp"

#include <omp.h>

namespace canopy {

ThreadLimit::ThreadLimit(int threads) : before_(omp_get_max_threads()), set_(threads > 0) {
  if (set_) omp_set_num_threads(threads);
}

ThreadLimit::~ThreadLimit() {
  if (set_) omp_set_num_threads(before_);
}

}  // namespace canopy
