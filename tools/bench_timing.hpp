#pragma once
/// Timing helpers of the benchmark programs (tools/bench_*, the FCL reference): seconds since a
/// time point, the median of repeated timings (the middle one after sorting, the upper of the
/// two middle ones for an even count), and the thread counts a benchmark runs at.
#include "geometry/clock.hpp"

#include <algorithm>
#include <chrono>
#include <vector>

namespace canopy {

/// The median of `times` (at least one).
inline double median(std::vector<double> times) {
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

/// The median wall time of `repeats` calls of f.
template <typename F>
double median_time(int repeats, F&& f) {
  std::vector<double> t;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    t.push_back(seconds_since(t0));
  }
  return median(std::move(t));
}

/// The thread counts of a benchmark's rows: one, then `all` where that is more (with one thread
/// available, the one-thread rows once).
inline std::vector<int> thread_counts(int all) {
  std::vector<int> counts{1};
  if (all > 1) counts.push_back(all);
  return counts;
}

}  // namespace canopy
