#pragma once
/// The resolution options of `canopy stand`, the run itself with its progress line, and its part
/// of report.json and of the terminal summary.
#include "resolution/resolve.hpp"
#include "tools/cli_common.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace canopy::cli {

struct ResolveOptions {
  bool no_resolve = false;
  int max_rounds = ResolveConfig{}.max_rounds;
  double clearance = ResolveConfig{}.clearance;
  std::string level = "exact";
  int candidates = ResolveConfig{}.candidates;
  int axis_fan = ResolveConfig{}.axis_fan;
  double scan_step = ResolveConfig{}.scan_step_deg;
  int bend_joints = ResolveConfig{}.bend_joints;
  double bend_step = ResolveConfig{}.bend_step_deg;
  bool progress = true;
  /// Off a terminal, a line a round once resolution has run kQuietSeconds (canopy stand printing;
  /// on a terminal the one line rewritten in place is shown either way).
  bool progress_lines = false;
  static constexpr double kQuietSeconds = 10;
  /// Plan with the host's candidate-by-candidate search even where the backend runs attempts in
  /// bulk (CUDA, or auto on a GPU: on the device, the default there). The turns are the same either way.
  bool host_search = false;
  /// Batches of contacts planned at once with the device's attempts (resolution/plan_round.hpp).
  int lanes = static_cast<int>(ResolveRequest{}.bulk_lanes);
  /// Print where resolution's time went on stderr when it ends (ResolveRequest::statistics).
  bool stats = false;

  void add_to(CLI::App& app);
  ResolveConfig config() const;
  nlohmann::ordered_json config_json() const;
};

/// Runs resolution with a progress line on stderr when it is a terminal (quiet otherwise).
/// `progress`, when set, replaces the terminal line. With `o.stats`, prints the statistics on
/// stderr at the end (tools/resolve_stats.hpp; over tiles, each process its own).
ResolveResult run_resolution(Stand& stand, DetectionBackend& backend, const DetectRequest& detect,
                             const ResolveOptions& o, const Contacts& initial,
                             std::function<void(const ResolveProgress&)> progress = {},
                             const ResolvePartition* partition = nullptr);

/// report.json's "resolution" object.
nlohmann::ordered_json resolution_json(const ResolveResult& r);
/// report.json's `resolution` with --no-resolve: the same fields as a loop of no rounds reports
/// (`ran` false, nothing turned, the contacts of `c` at its level before and after), so a reader
/// of `resolution.iterations` finds it either way.
nlohmann::ordered_json resolution_not_run_json(const Contacts& c);
void print_resolution(const ResolveResult& r);

}  // namespace canopy::cli
