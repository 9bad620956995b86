#pragma once
/// Where a resolution's time went, when ResolveRequest::statistics asks for it: its phases over
/// all rounds, its lanes of planning, and the runner of its bulk attempts. The library collects
/// them into ResolveResult::stats and prints nothing; the tools print them
/// (`canopy stand --resolve-stats`, tools/resolve_stats.hpp).
#include "resolution/attempt_batch.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace canopy {

/// One phase of resolution summed over its rounds (resolution/phase_times.hpp).
struct PhaseStat {
  std::string name;
  double wall_s = 0, cpu_s = 0;  // the process's CPU seconds, all threads
  long minor_faults = 0;
};

/// One lane of planning, summed over the rounds (resolution/plan_round.hpp).
struct PlanLaneStats {
  double batch_s = 0;           // in batches
  double prepare_s = 0;         // preparing and scanning candidates on the host
  std::size_t levels = 0;       // cost levels run
  std::size_t host_levels = 0;  // of them, searched on the host (all, or with a runner the small ones)
  std::size_t handed_over = 0;  // candidates the runner found and the host refined (at a switch)
  /// Levels and their seconds by how many candidates each scanned or refined: fewer than 16,
  /// 256, 4,096, and more (a level's round trips to a runner cost the same for 1 or 10,000).
  static constexpr std::size_t kLevelSizes = 4;
  std::array<std::size_t, kLevelSizes> levels_by_size{};
  std::array<double, kLevelSizes> seconds_by_size{};
  static std::size_t size_class(std::size_t candidates) {
    return candidates < 16 ? 0 : candidates < 256 ? 1 : candidates < 4096 ? 2 : 3;
  }
  /// With bulk attempts (resolution/batched_scan.hpp): scanning and refining, of which the
  /// joint-limit checks, the table writes, the neighbour gathers (`gathers` of them) and the
  /// runner's calls.
  double scan_s = 0, limits_s = 0, tables_s = 0, gather_s = 0, runner_s = 0;
  std::size_t gathers = 0;
  /// The memory the lane's tables held when resolution ended, bytes: moving organs, kept organs,
  /// pairs, witnesses, axes.
  std::size_t moving_bytes = 0, keep_bytes = 0, pair_bytes = 0, witness_bytes = 0, axis_bytes = 0;
};

struct ResolveStats {
  bool collected = false;  // ResolveRequest::statistics was set
  int threads = 0;
  /// setup, witnesses, candidates, bookkeeping, scan, pick, last resort, apply turns, refit,
  /// redetect, merge, release.
  std::vector<PhaseStat> phases;
  /// The candidates' scan times summed over the threads: scan_busy_s / (threads x the scan
  /// phase's wall_s) is the scan's parallel share.
  double scan_busy_s = 0;
  std::vector<PlanLaneStats> lanes;
  std::optional<AttemptStats> attempts;  // the runner's, where one planned
};

}  // namespace canopy
