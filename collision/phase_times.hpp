#pragma once
/// Resolution's own stopwatch: wall and CPU seconds and page faults per phase over all rounds.
#include "geometry/clock.hpp"

#include <cstdlib>

namespace canopy {

/// Where resolution's time goes, phase by phase over all rounds, printed at its end when
/// CANOPY_PLAN_STATS is set (off: one branch per phase); `scan_busy` sums the candidates'
/// scan times over the threads, so scan_busy / (threads x scan) is the scan's parallel share.
struct PhaseTimes {
  enum Phase { setup, witnesses, candidates, bookkeeping, scan, pick, last_resort, apply, refit, redetect, merge, release, count };
  bool on = std::getenv("CANOPY_PLAN_STATS") != nullptr;
  double seconds[count] = {}, scan_busy = 0, mark = now_seconds();
  /// The process's CPU seconds (all threads) and minor page faults so far (one getrusage).
  struct Usage {
    double cpu = 0;
    long faults = 0;
  };
  double cpu[count] = {};   // per phase
  long faults[count] = {};  // per phase
  Usage usage_mark = usage();
  void lap(Phase p);
  void print(int threads) const;
  static Usage usage();
};

}  // namespace canopy
