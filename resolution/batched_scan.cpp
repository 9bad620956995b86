#include "resolution/batched_scan.hpp"

#include "geometry/clock.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace canopy {
namespace {

constexpr double kRad = std::numbers::pi / 180;
/// Axes per group (the width of AttemptGroup::axis_mask).
constexpr std::size_t kGroupAxes = 32;
/// Candidates from which a loop over them runs on all threads (a level of 10,000 plants has
/// tens of thousands; small ones are not worth waking the threads for).
constexpr std::size_t kParallelFrom = 2048;

using Candidate = TurnSearch::Candidate;

/// Adds the seconds of its scope to `sum` (PlanLaneStats).
struct Timed {
  double& sum;
  double start = now_seconds();
  ~Timed() { sum += now_seconds() - start; }
};

}  // namespace

void BatchedScan::add_stats(PlanLaneStats& to) const {
  to.scan_s += times_.scan, to.limits_s += times_.limits, to.tables_s += times_.tables;
  to.gather_s += times_.gather, to.runner_s += times_.runner, to.gathers += times_.gathers;
}

void BatchedScan::clear() {
  tables_.clear();
  runner_.clear(lane_);
}

void BatchedScan::add_tables(std::span<Candidate* const> cands, bool near) {
  const Timed timed{times_.tables};
  // Sizes first, then every candidate's entries written in parallel into its own ranges.
  std::vector<Candidate*> add;
  for (Candidate* c : cands)
    if (near ? c->strict && c->near_deg >= 0 && c->tables.near_deg != c->near_deg
             : c->tables.moving == kNoPair)
      add.push_back(c);
  if (add.empty()) return;
  std::size_t n_moving = tables_.moving.size(), n_keep = tables_.keep.size(), n_pairs = tables_.pairs.size(),
              n_axes = tables_.axes.size();
  for (Candidate* c : add) {
    Candidate::Tables& t = c->tables;
    if (!near) {
      t.moving = static_cast<std::uint32_t>(n_moving), t.axes = static_cast<std::uint32_t>(n_axes);
      t.met_first = static_cast<std::uint32_t>(n_pairs);
      n_moving += c->moving.size(), n_axes += c->axes.size(), n_keep += c->met_count,
          n_pairs += c->met_pairs.y.size();
      t.met_end = static_cast<std::uint32_t>(n_pairs);
    } else {
      t.near_first = static_cast<std::uint32_t>(n_pairs), t.near_deg = c->near_deg;
      n_keep += c->keep.size() - c->met_count, n_pairs += c->near_pairs.y.size();
      t.near_end = static_cast<std::uint32_t>(n_pairs);
    }
  }
  // Keep slots: where each candidate's first new keep entry goes.
  std::vector<std::uint32_t> keep_at(add.size());
  {
    std::size_t k = tables_.keep.size();
    for (std::size_t j = 0; j < add.size(); ++j)
      keep_at[j] = static_cast<std::uint32_t>(k),
      k += near ? add[j]->keep.size() - add[j]->met_count : add[j]->met_count;
  }
  // Every new entry is written below (the tables' allocator leaves them unwritten until then).
  tables_.moving.resize(n_moving), tables_.keep.resize(n_keep), tables_.pairs.resize(n_pairs),
      tables_.axes.resize(n_axes);
  tables_.witness.resize(n_pairs);
#pragma omp parallel for schedule(dynamic, 64) num_threads(threads_)
  for (std::size_t j = 0; j < add.size(); ++j) {
    const Candidate& c = *add[j];
    const Candidate::Tables& t = c.tables;
    const std::size_t keep_from = near ? c.met_count : 0, keep_to = near ? c.keep.size() : c.met_count;
    for (std::size_t i = keep_from; i < keep_to; ++i) {
      const std::int32_t y = c.keep[i];
      tables_.keep[keep_at[j] + (i - keep_from)] =
          KeepEntry{y, i < c.met_count ? search_.clearance : search_.detect_clearance, c.keep_off[i]};
    }
    const TurnSearch::PairSet& pairs = near ? c.near_pairs : c.met_pairs;
    std::uint32_t at = near ? t.near_first : t.met_first;
    for (std::size_t i = 0; i < c.moving.size(); ++i)
      for (std::uint32_t p = pairs.first[i]; p < pairs.first[i + 1]; ++p) {
        // The witness the round began with (the organs met touched then; neighbours did not,
        // and have none on the candidate).
        const Witness* w = pairs.find(p);
        tables_.witness[at] =
            w && w->latest >= 0 ? std::uint32_t{w->tri_a[w->latest]} << 16 | w->tri_b[w->latest] : kNoWitness;
        tables_.pairs[at++] = PairEntry{t.moving + static_cast<std::uint32_t>(i),
                                        keep_at[j] + static_cast<std::uint32_t>(pairs.y[p] - keep_from)};
      }
    if (near) continue;
    std::copy(c.moving.begin(), c.moving.end(), tables_.moving.begin() + t.moving);
    std::copy(c.axes.begin(), c.axes.end(), tables_.axes.begin() + t.axes);
  }
}

std::vector<std::uint32_t> BatchedScan::clear_axes(std::span<Candidate* const> cands,
                                                   std::span<const double> deg,
                                                   std::span<const AxisSet> want) {
  const AttemptSettings settings{search_.clearance, search_.config.level != ContactLevel::organ};
  std::vector<std::uint32_t> ok(cands.size(), 0);
  // The turn's cosine and sine, once per candidate (the met and the near groups share them).
  std::vector<double> cos(cands.size()), sin(cands.size());
#pragma omp parallel for schedule(static) num_threads(threads_) if (cands.size() > kParallelFrom)
  for (std::size_t j = 0; j < cands.size(); ++j)
    cos[j] = std::cos(deg[j] * kRad), sin[j] = std::sin(deg[j] * kRad);
  const auto group_of = [&](std::size_t j, bool near, std::uint32_t mask) {
    const Candidate::Tables& t = cands[j]->tables;
    AttemptGroup g;
    g.joint = cands[j]->joint;
    g.cos = cos[j], g.sin = sin[j];
    g.axis_first = t.axes + want[j].first;
    g.pair_first = near ? t.near_first : t.met_first;
    g.pair_end = near ? t.near_end : t.met_end;
    g.axis_mask = mask;
    return g;
  };
  const auto touching = [&](const std::vector<AttemptGroup>& groups) {
    const Timed timed{times_.runner};
    return runner_.touching(lane_, tables_, groups, settings);
  };
  // The organs met, for every axis wanted.
  add_tables(cands, false);
  std::vector<std::size_t> of;
  for (std::size_t j = 0; j < cands.size(); ++j)
    if (want[j].mask) of.push_back(j);
  std::vector<AttemptGroup> groups(of.size());
#pragma omp parallel for schedule(static) num_threads(threads_) if (of.size() > kParallelFrom)
  for (std::size_t q = 0; q < of.size(); ++q) groups[q] = group_of(of[q], false, want[of[q]].mask);
  std::vector<std::uint32_t> touch = touching(groups);
  for (std::size_t q = 0; q < groups.size(); ++q) ok[of[q]] = groups[q].axis_mask & ~touch[q];
  // A strict search's neighbours, for the axes that cleared the organs met (gathered, as the
  // host search gathers them, when a turn first clears those and the gathered ones do not cover it).
  std::vector<Candidate*> strict;
  std::vector<std::size_t> strict_of, to_gather;
  for (std::size_t j = 0; j < cands.size(); ++j)
    if (ok[j] && cands[j]->strict) {
      if (cands[j]->near_deg < deg[j]) to_gather.push_back(j);
      strict.push_back(cands[j]), strict_of.push_back(j);
    }
  if (strict.empty()) return ok;
  {
    const Timed timed{times_.gather};
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads_)
    for (std::size_t q = 0; q < to_gather.size(); ++q)
      search_.gather_neighbours(*cands[to_gather[q]], deg[to_gather[q]]);
  }
  times_.gathers += to_gather.size();
  add_tables(strict, true);
  groups.clear(), of.clear();
  for (std::size_t j : strict_of) {
    const AttemptGroup g = group_of(j, true, ok[j]);
    if (g.pair_first == g.pair_end) continue;  // no neighbour within reach: nothing to clear
    groups.push_back(g), of.push_back(j);
  }
  touch = touching(groups);
  for (std::size_t q = 0; q < groups.size(); ++q) ok[of[q]] &= ~touch[q];
  return ok;
}

std::vector<Turn> BatchedScan::scan_and_refine(std::span<Candidate* const> scan, int level,
                                               std::span<Candidate* const> refine) {
  const Timed timed{times_.scan};
  const ResolveConfig& cfg = search_.config;
  const double step = std::max(cfg.scan_step_deg, cfg.angle_tolerance_deg), tol = cfg.angle_tolerance_deg;
  // The scan (TurnSearch::scan_level): every candidate still searching, at the level's angle.
  std::vector<Candidate*> live;
  std::vector<double> level_deg;
  for (Candidate* c : scan)
    if (c->searching())
      live.push_back(c), level_deg.push_back(std::min(level * step / c->weight, c->reach_deg));
  // The refinement (TurnSearch::refine): each found candidate's bracket, lo failing, hi separating.
  std::vector<double> lo(refine.size()), hi(refine.size());
  for (std::size_t j = 0; j < refine.size(); ++j) {
    lo[j] = refine[j]->lo, hi[j] = refine[j]->hi;
    // The neighbours gathered cover the found angle, so no midpoint gathers (clear_axes below
    // takes a candidate several times, and gathering is not safe for that).
    if (refine[j]->strict && refine[j]->near_deg < hi[j])
      throw std::logic_error("batched scan: neighbours do not cover a found turn");
  }
  // The bisection (while hi - lo > tol, test the midpoint and keep the half with a failing end
  // and a separating end) answered a few steps at a time: every midpoint the next kSpeculate
  // steps could visit, as a tree (a separating midpoint leads to the left half, a failing one to
  // the right; a half no wider than the tolerance ends its branch), tested in one call, then
  // walked as the one-step-at-a-time bisection walks it. The same midpoints, 0.5 (lo + hi) of
  // the same ends, so the same turns, for up to 7 attempts where the walk makes 3 but one round
  // trip to the runner instead of 3.
  constexpr int kSpeculate = 3;
  struct Node {
    double lo, hi;
    std::int32_t left = -1, right = -1, depth = 0;
  };
  // Each call: the scan's next chunk of axes (a group's width; each candidate takes the first
  // axis that clears) and the refinement's next round of midpoints. The two sets of candidates
  // are apart (a found candidate scans no more), and an attempt's answer depends on its own
  // candidate alone, so they share the calls' round trips and every answer is what each would
  // get alone.
  for (std::size_t first = 0;; first += kGroupAxes) {
    std::vector<Candidate*> act;
    std::vector<double> deg;
    for (std::size_t j = 0; j < live.size(); ++j)
      if (live[j]->found_axis < 0 && live[j]->axes.size() > first)
        act.push_back(live[j]), deg.push_back(level_deg[j]);
    const std::size_t n_scan = act.size();
    std::vector<std::uint32_t> tree_first{0};
    std::vector<std::size_t> of;  // per tree: its candidate
    std::vector<Node> nodes;
    for (std::size_t j = 0; j < refine.size(); ++j) {
      if (!(hi[j] - lo[j] > tol)) continue;
      of.push_back(j);
      nodes.push_back(Node{lo[j], hi[j]});
      for (std::size_t n = tree_first.back(); n < nodes.size(); ++n) {
        const Node at = nodes[n];
        if (at.depth + 1 >= kSpeculate) continue;
        const double mid = 0.5 * (at.lo + at.hi);
        if (mid - at.lo > tol)
          nodes[n].left = static_cast<std::int32_t>(nodes.size()),
          nodes.push_back(Node{at.lo, mid, -1, -1, at.depth + 1});
        if (at.hi - mid > tol)
          nodes[n].right = static_cast<std::int32_t>(nodes.size()),
          nodes.push_back(Node{mid, at.hi, -1, -1, at.depth + 1});
      }
      tree_first.push_back(static_cast<std::uint32_t>(nodes.size()));
    }
    if (n_scan == 0 && of.empty()) break;
    act.resize(n_scan + nodes.size()), deg.resize(n_scan + nodes.size());
    std::vector<AxisSet> want(act.size());
    {
      const Timed timed{times_.limits};
#pragma omp parallel for schedule(dynamic, 64) num_threads(threads_)
      for (std::size_t j = 0; j < n_scan; ++j) {
        Candidate& c = *act[j];
        want[j].first = static_cast<std::uint32_t>(first);
        const std::size_t end = std::min(c.axes.size(), first + kGroupAxes);
        for (std::size_t i = first; i < end; ++i)
          if (search_.within_limit(c, c.axes[i], deg[j])) want[j].mask |= 1u << (i - first);
      }
      // Every node's midpoint, its candidate and whether its joint stays within the limit there
      // (a candidate's nodes by one thread: the turn's cosine and sine are kept in the candidate).
#pragma omp parallel for schedule(static) num_threads(threads_) if (of.size() > kParallelFrom)
      for (std::size_t t = 0; t < of.size(); ++t) {
        Candidate& c = *refine[of[t]];
        const auto a = static_cast<std::size_t>(c.found_axis);
        for (std::uint32_t n = tree_first[t]; n < tree_first[t + 1]; ++n) {
          const std::size_t at = n_scan + n;
          act[at] = &c, deg[at] = 0.5 * (nodes[n].lo + nodes[n].hi);
          want[at] =
              AxisSet{static_cast<std::uint32_t>(a), search_.within_limit(c, c.axes[a], deg[at]) ? 1u : 0u};
        }
      }
    }
    const std::vector<std::uint32_t> ok = clear_axes(act, deg, want);
#pragma omp parallel for schedule(static) num_threads(threads_) if (n_scan > kParallelFrom)
    for (std::size_t j = 0; j < n_scan; ++j) {
      if (!ok[j]) continue;
      Candidate& c = *act[j];
      c.found_axis = static_cast<int>(first) + std::countr_zero(ok[j]);
      c.hi = deg[j];
      c.local = search_.local_after(c, c.axes[static_cast<std::size_t>(c.found_axis)], deg[j]);
    }
    for (std::size_t t = 0; t < of.size(); ++t) {
      const std::size_t j = of[t];
      for (std::int32_t n = static_cast<std::int32_t>(tree_first[t]); n >= 0;) {
        const auto at = static_cast<std::size_t>(n);
        if (ok[n_scan + at]) hi[j] = deg[n_scan + at], n = nodes[at].left;
        else lo[j] = deg[n_scan + at], n = nodes[at].right;
      }
    }
  }
  for (std::size_t j = 0; j < live.size(); ++j)
    if (live[j]->found_axis < 0) live[j]->lo = level_deg[j];
  std::vector<Turn> out(refine.size());
#pragma omp parallel for schedule(static) num_threads(threads_) if (refine.size() > kParallelFrom)
  for (std::size_t j = 0; j < refine.size(); ++j) {
    Candidate& c = *refine[j];
    // The joint's rotation at the last separating midpoint, or the scan's where none separated.
    const Mat3d best = hi[j] != c.hi
                           ? search_.local_after(c, c.axes[static_cast<std::size_t>(c.found_axis)], hi[j])
                           : c.local;
    out[j] = Turn{c.mover, best, hi[j]};
  }
  return out;
}

}  // namespace canopy
