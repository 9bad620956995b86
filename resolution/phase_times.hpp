#pragma once
/// Resolution's own stopwatch: wall and CPU seconds and page faults per phase over all rounds.
#include "resolution/resolve_stats.hpp"
#include "geometry/clock.hpp"

#include <vector>

namespace canopy {

/// Where resolution's time goes, phase by phase over all rounds, when `on`
/// (ResolveRequest::statistics; off: one branch per phase); `scan_busy` sums the candidates'
/// scan times over the threads, so scan_busy / (threads x scan) is the scan's parallel share.
struct PhaseTimes {
  enum Phase {
    setup,
    witnesses,
    candidates,
    bookkeeping,
    scan,
    pick,
    last_resort,
    apply,
    refit,
    redetect,
    merge,
    release,
    count
  };
  explicit PhaseTimes(bool on = false) : on(on) {}
  bool on;
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
  /// Every phase's sums, in the order of Phase.
  std::vector<PhaseStat> phases() const;
  static Usage usage();
};

}  // namespace canopy
