#pragma once
// Appending to a device list of fixed capacity: the threads of a warp that append together take
// their slots with one atomic add (warp-aggregated, so a crowded list does not serialise on one
// counter); items past the capacity are counted, not written (the host grows the list and runs
// again). The order of items is not fixed: every list is sorted afterwards.
#include "cuda/detect_kernels.hpp"

#include <cooperative_groups.h>

namespace canopy::cuda {

template <typename T>
__device__ inline void append(T* out, unsigned long long capacity, Counters* c, const T& item) {
  const cooperative_groups::coalesced_group g = cooperative_groups::coalesced_threads();
  unsigned long long base = 0;
  if (g.thread_rank() == 0) base = atomicAdd(&c->appended, static_cast<unsigned long long>(g.size()));
  const unsigned long long at = g.shfl(base, 0) + g.thread_rank();
  if (at < capacity) out[at] = item;
}

}  // namespace canopy::cuda
