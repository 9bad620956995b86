#pragma once
/// `canopy sweep` as a library call, shared by the command line and the Python module.
#include "geometry/prototype.hpp"
#include "lsystem/grow.hpp"
#include "tools/detect_options.hpp"
#include "tools/resolve_options.hpp"
#include "tools/sweep_table.hpp"

#include <CLI/CLI.hpp>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace canopy::cli {

/// The runs (cells x seeds) a sweep takes at most: a million runs of the smallest stand are days.
inline constexpr double kMaxSweepRuns = 1e6;

/// Every option of `canopy sweep` (the command line's names).
struct SweepOptions {
  std::string grammar, out = "sweep";
  std::string plant_spacing = "0.4", row_spacing = "1.0", density, steps;
  int seeds = 3, rows = 3, per_row = 5;
  /// Jitter radius (metres) and whether plants are turned at random: unset, the grammar's stand
  /// entry's, else 0.02 and turned (docs/design.md's default stand). Rows, plants per row, the
  /// spacings and the seed are the sweep's own.
  std::optional<double> jitter;
  std::optional<bool> random_rotation;
  int lod = kDefaultLod;
  std::vector<std::string> set;
  bool retry_failed = false;
  std::size_t max_modules = kDefaultMaxModules;
  DetectOptions detect;
  ResolveOptions resolve;
  // Light of each run before and after resolution (tools/sweep_light.hpp).
  std::string sun = "60,180";  // ELEVATION,AZIMUTH of the direct beam
  std::string sky = "soc";
  int sky_directions = 46;
  double light_error = 0.002;
  bool no_light = false;
};

struct SweepOutcome {
  std::size_t total = 0, ran = 0, failed = 0;
  std::size_t failed_in_table =
      0;  // runs.csv's failed rows of this call's grid, this call's and earlier ones
  bool interrupted = false;
  int exit_code = 0;               // 0, 3 (runs.csv holds failed runs of the grid) or 130 (interrupted)
  std::vector<std::string> notes;  // the grammar's (Grammar::notes), printed when the sweep prints
};

/// Called after each run made (its row already in runs.csv): run index, total runs, the row.
/// Throwing from it stops the sweep after that run; summary.csv is still written.
using SweepCallback = std::function<void(std::size_t, std::size_t, const RunRow&)>;

/// Several processes sharing one sweep (canopy sweep under mpirun): each runs every size-th
/// pending run; rank 0 appends the rows to runs.csv in run order after each wave.
struct SweepRanks {
  int rank = 0, size = 1, local_rank = 0;
  /// Collective: every rank's string, in rank order.
  std::function<std::vector<std::string>(const std::string&)> gather;
};

SweepOutcome run_sweep(const SweepOptions& o, bool print = true, const SweepCallback& after_run = {},
                       const SweepRanks* ranks = nullptr);

/// `canopy sweep`'s arguments and options registered on `app` (the subcommand, or an app of the
/// Python module's own).
std::shared_ptr<SweepOptions> register_sweep(CLI::App& app);

}  // namespace canopy::cli
