#include "tools/resolve_stats.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace canopy::cli {
namespace {

/// Sums of the phases' CPU seconds from `first` to `last` (indices into the phases, in order).
double cpu_of(const ResolveStats& s, std::size_t first, std::size_t last) {
  double sum = 0;
  for (std::size_t p = first; p <= last && p < s.phases.size(); ++p) sum += s.phases[p].cpu_s;
  return sum;
}

std::string runner_text(const AttemptStats& a) {
  std::string out = fmt::format(
      "resolution's bulk attempts ({}, {} lanes): {} calls, {} groups, {} box tests, {} witness hits, {} "
      "exact tests ({} "
      "touching), {:.1f} MB up; {:.3f} s in calls ({:.3f} up, {:.3f} boxes, {:.3f} exact)\n",
      a.hardware, a.lanes, a.calls, a.groups, a.box_tests, a.witness_hits, a.exact_tests, a.exact_touches,
      1e-6 * static_cast<double>(a.uploaded_bytes), a.call_s, a.upload_s, a.box_s, a.exact_s);
  if (a.timeline)
    out += fmt::format(
        "resolution's bulk attempts' kernels: {:.3f} s from the first call's to the last's, some lane's "
        "queued or running {:.3f} "
        "s "
        "of it ({:.0f} %), the calls' spans summed {:.3f} s\n",
        a.kernels_span_s, a.kernels_busy_s, 100 * a.kernels_busy_s / std::max(a.kernels_span_s, 1e-9),
        a.kernels_summed_s);
  else if (!a.no_timeline.empty())
    out += fmt::format("resolution's bulk attempts' kernels: no timeline ({})\n", a.no_timeline);
  return out;
}

}  // namespace

std::string resolve_stats_text(const ResolveStats& s) {
  if (!s.collected) return {};
  std::string out = "resolution phases (s):";
  for (const PhaseStat& p : s.phases)
    out += fmt::format("{} {} {:.3f}", &p == &s.phases.front() ? "" : ",", p.name, p.wall_s);
  // The phases in PhaseTimes' order: setup, witnesses, candidates | bookkeeping, scan | pick ... release.
  out += fmt::format(
      "; scan busy {:.2f} thread-s on {} threads; CPU s (all threads) setup to candidates {:.2f}, scan "
      "{:.2f}, the "
      "rest {:.2f}\n",
      s.scan_busy_s, s.threads, cpu_of(s, 0, 2), cpu_of(s, 4, 4),
      cpu_of(s, 3, 3) + cpu_of(s, 5, s.phases.size()));
  out += "resolution minor page faults (thousands):";
  for (const PhaseStat& p : s.phases)
    out += fmt::format("{} {} {:.1f}", &p == &s.phases.front() ? "" : ",", p.name,
                       1e-3 * static_cast<double>(p.minor_faults));
  out += "\n";
  for (std::size_t l = 0; l < s.lanes.size(); ++l) {
    const PlanLaneStats& x = s.lanes[l];
    out += fmt::format(
        "planning lane {}: {:.3f} s in batches, {} levels ({} of them on the host, {} finds handed to it), "
        "candidates prepared in {:.3f} s\n",
        l, x.batch_s, x.levels, x.host_levels, x.handed_over, x.prepare_s);
    out += fmt::format(
        "planning lane {} levels by candidates (<16, <256, <4096, more): {} in {:.3f} s, {} in {:.3f} s, {} "
        "in "
        "{:.3f} s, {} in {:.3f} s\n",
        l, x.levels_by_size[0], x.seconds_by_size[0], x.levels_by_size[1], x.seconds_by_size[1],
        x.levels_by_size[2], x.seconds_by_size[2], x.levels_by_size[3], x.seconds_by_size[3]);
    if (x.scan_s == 0 && x.moving_bytes == 0) continue;  // the host's search: no batched scan
    out += fmt::format(
        "batched scan (lane {}): scan and refine {:.3f} s, of which limits {:.3f} s, tables {:.3f} s, {} "
        "gathers "
        "{:.3f} s, runner {:.3f} s; tables held (MB): moving {:.1f}, keep {:.1f}, pairs {:.1f}, witness "
        "{:.1f}, "
        "axes {:.1f}\n",
        l, x.scan_s, x.limits_s, x.tables_s, x.gathers, x.gather_s, x.runner_s,
        1e-6 * static_cast<double>(x.moving_bytes), 1e-6 * static_cast<double>(x.keep_bytes),
        1e-6 * static_cast<double>(x.pair_bytes), 1e-6 * static_cast<double>(x.witness_bytes),
        1e-6 * static_cast<double>(x.axis_bytes));
  }
  if (s.attempts) out += runner_text(*s.attempts);
  return out;
}

}  // namespace canopy::cli
