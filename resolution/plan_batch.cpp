#include "resolution/plan_batch.hpp"

#include "geometry/first_exception.hpp"

#include "resolution/resolve_policy.hpp"
#include "geometry/clock.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>

namespace canopy::planning {
namespace {

/// Every contact of the round with exactly one organ in `mover`'s subtree: what a turn of that
/// mover must separate (several contacts on one organ are combined into one turn).
const MetPairs& contacts_of(const Joints& joints, const ContactGraph& g, std::uint32_t mover) {
  thread_local MetPairs met;  // the list's memory kept per thread (asked once per candidate)
  met.clear();
  const std::uint32_t end = joints.subtree_end(mover);
  for (std::uint32_t x = mover; x < end; ++x)
    for (std::uint32_t e = g.first[x]; e < g.first[x + 1]; ++e) {
      const std::int32_t y = g.with[e];
      if (!joints.holds(mover, y)) met.emplace_back(static_cast<std::int32_t>(x), y);
    }
  return met;
}

}  // namespace

Picks Round::plan_batch(Lane& lane, std::span<const std::size_t> batch, bool strict) {
  PhaseTimes& times = *lane.times;
  const int threads = lane.threads;
  std::vector<std::size_t>& slots = lane.slots;
  std::vector<std::uint32_t>& local_of = lane.local_of;
  slots.clear();
  for (std::size_t i : batch)
    for (std::size_t g : cand_slots[i])
      if (local_of[g] == kNoPair) local_of[g] = 0, slots.push_back(g);
  std::sort(slots.begin(), slots.end());
  for (std::size_t k = 0; k < slots.size(); ++k) local_of[slots[k]] = static_cast<std::uint32_t>(k);
  // Each contact's candidates as indices into the batch's movers, found once: those of
  // batch[q] are cand_local[local_first[q], local_first[q + 1]). Pending: values of q.
  std::vector<std::uint32_t> local_first{0}, cand_local, pending;
  for (std::size_t q = 0; q < batch.size(); ++q) {
    pending.push_back(static_cast<std::uint32_t>(q));
    for (std::size_t g : cand_slots[batch[q]]) cand_local.push_back(local_of[g]);
    local_first.push_back(static_cast<std::uint32_t>(cand_local.size()));
  }
  for (std::size_t g : slots) local_of[g] = kNoPair;
  const auto candidates_of = [&](std::uint32_t q) {
    return std::span<const std::uint32_t>(cand_local.data() + local_first[q],
                                          local_first[q + 1] - local_first[q]);
  };
  std::vector<TurnSearch::Candidate*>& state = lane.state;
  std::vector<std::uint8_t>&open = lane.open, &want = lane.want, &handed = lane.handed;
  std::vector<std::optional<Turn>>& refined = lane.refined;
  state.assign(slots.size(), nullptr);
  open.assign(slots.size(), 1);
  want.assign(slots.size(), 0);
  handed.assign(slots.size(), 0);
  refined.assign(slots.size(), std::nullopt);
  std::vector<CandidatePool>& pools = *lane.pools;
  for (CandidatePool& p : pools) p.used = 0;  // the last batch's candidates are free again
  if (lane.bulk) lane.bulk->clear();
  const double batch_start = now_seconds();
  std::vector<std::size_t> chosen;
  // Bulk: the candidates found at the last level, refined in this level's calls (with its scan).
  // Their contacts are settled (a contact with a candidate found is resolved, whatever the
  // refined angles), so they want no scan, and are picked once the refined turns are back: the
  // same contacts scanned at every level and the same picks, one level later.
  std::vector<std::size_t> unrefined;
  // Candidates that carry long chains (hundreds of organs each on average) are searched on the
  // host from the first level: each attempt's witnesses end most of their tests early there,
  // where the runner's tables carry every subtree organ's pairs (a plant of one coiled 2,000-segment
  // chain: 5.0 s and 2.5 GB through the device's lanes, 1.1 s and 0.42 GB on the host's search).
  // The turns are the same either way.
  std::size_t carried = 0;
  for (std::size_t g : slots) carried += joints.subtree_end(movers[g]) - movers[g];
  const bool heavy = carried > request.host_carried * slots.size();
  for (int level = 1; !pending.empty(); ++level) {
    const double level_start = now_seconds();
    tell(0);
    std::fill(want.begin(), want.end(), 0);
    for (std::size_t k : unrefined) want[k] = 2;
    for (std::uint32_t q : pending) {
      const std::span<const std::uint32_t> ks = candidates_of(q);
      if (std::any_of(ks.begin(), ks.end(), [&](std::uint32_t k) { return want[k] == 2; }))
        continue;  // settled
      for (std::uint32_t k : ks) want[k] |= open[k];
    }
    std::vector<std::size_t> scan;
    for (std::size_t k = 0; k < slots.size(); ++k)
      if (want[k] == 1) scan.push_back(k);
    if (scan.empty() && unrefined.empty()) break;
    ++lane.levels;
    const std::size_t level_size = scan.size() + unrefined.size();  // candidates scanned or refined
    // A level searched on the host: every level without a runner, and a runner's levels once
    // they are small (PlanRequest::host_levels_below). The last level's finds are refined here
    // then, and this level's at once, as the host's search does: a contact picks the same turn
    // at the level where its candidate was found instead of the next, the same turn either way.
    const bool host = !lane.bulk || heavy || level_size < request.host_levels_below;
    if (host) ++lane.host_levels;
    // The runner's finds of the last level handed to the host: their contacts pick among them
    // alone, as they would have at this level through the runner (a candidate that this level
    // finds for another contact costs more, but could tie to the last bit near its reach). This
    // happens once a batch at most (the host keeps every later level, and leaves nothing
    // unrefined), so the marks are read only at the level that sets them.
    const bool handing = host && !unrefined.empty();
    if (handing) {
      for (std::size_t k : unrefined) scan.push_back(k), handed[k] = 1;
      lane.handed_over += unrefined.size();
      unrefined.clear();
    }
    // Neighbouring candidates (organs of one leaf) test against the same organs: a thread
    // that takes a few in a row finds their poses in its cache. Chunks of up to 8, fewer
    // where the level is short, so that no thread waits long at its end.
    const int chunk = static_cast<int>(
        std::clamp<std::size_t>(scan.size() / (16 * static_cast<std::size_t>(threads)), 1, 8));
    times.lap(PhaseTimes::bookkeeping);
    const double prepare_start = now_seconds();
    // The candidates' lists (each carries its subtree) are where memory grows without a bound
    // known before: checked every few candidates made, the level's others skipped once past it.
    std::atomic<bool> outgrown{false};
    // What a thread meets (out of memory in a candidate's lists) may not leave the region.
    FirstException error;
#pragma omp parallel for schedule(dynamic, chunk) num_threads(threads)
    for (std::size_t j = 0; j < scan.size(); ++j) try {
        if (outgrown.load(std::memory_order_relaxed) || error.caught()) continue;
        const double started = times.on ? now_seconds() : 0;
        const std::size_t k = scan[j];
        const std::uint32_t m = movers[slots[k]];
        const auto me = static_cast<std::size_t>(omp_get_thread_num());
        if (!state[k]) {
          state[k] = pools[me].take(), search.prepare(*state[k], m, contacts_of(joints, graph, m), strict);
          thread_local unsigned made = 0;
          if (request.ceiling && ++made % 32 == 0 && request.ceiling->over()) {
            outgrown = true;
            continue;
          }
        }
        // Found (now, or by the runner at the last level): refined to its smallest turn at once,
        // by the same thread (it depends on the candidate alone).
        if (host && search.scan_level(*state[k], level, (*lane.scratches)[me]))
          refined[k] = search.refine(*state[k], (*lane.scratches)[me]);
        open[k] = state[k]->searching();
        if (times.on) {
          const double busy = now_seconds() - started;
#pragma omp atomic
        times.scan_busy += busy;
      }
      } catch (...) {
        error.keep();
      }
    error.rethrow();
    lane.prepare_s += now_seconds() - prepare_start;
    if (outgrown) request.ceiling->refuse("resolution's candidate turns");
    const auto candidates = [&](const std::vector<std::size_t>& ks) {
      std::vector<TurnSearch::Candidate*> out;
      for (std::size_t k : ks) out.push_back(state[k]);
      return out;
    };
    if (!host) {
      // This level's scan, and the last level's finds each refined to its smallest turn, once.
      const std::vector<Turn> turns =
          lane.bulk->scan_and_refine(candidates(scan), level, candidates(unrefined));
      for (std::size_t j = 0; j < unrefined.size(); ++j) refined[unrefined[j]] = turns[j];
      unrefined.clear();
      for (std::size_t k : scan)
        if (state[k]->found_axis >= 0 && !refined[k]) unrefined.push_back(k);
      for (std::size_t k : scan) open[k] = state[k]->searching();
    }
    times.lap(PhaseTimes::scan);  // with the batched scan's own work
    // Each contact with a candidate found takes the cheapest (angle x weight; ties: policy order).
    const std::size_t before = pending.size();
    std::erase_if(pending, [&](std::uint32_t q) {
      std::optional<std::size_t> pick;
      double cost = 0;
      const std::span<const std::uint32_t> ks = candidates_of(q);
      const bool settled =
          handing && std::any_of(ks.begin(), ks.end(), [&](std::uint32_t k) { return handed[k]; });
      for (std::uint32_t k : ks) {
        if (!refined[k] || (settled && !handed[k])) continue;
        const double c = refined[k]->angle_deg * state[k]->weight;
        if (!pick || c < cost) pick = k, cost = c;
      }
      if (!pick) return false;
      resolved[batch[q]] = 1;
      chosen.push_back(*pick);
      return true;
    });
    unplanned -= before - pending.size();
    times.lap(PhaseTimes::pick);
    const std::size_t size_class = PlanLaneStats::size_class(level_size);
    ++lane.levels_by_size[size_class];
    lane.seconds_by_size[size_class] += now_seconds() - level_start;
  }
  unplanned -= pending.size();  // left to the relaxed pass or the last resort
  lane.batch_s += now_seconds() - batch_start;
  Picks out;
  for (std::size_t k : chosen) out.emplace_back(slots[k], *refined[k]);
  return out;
}

}  // namespace canopy::planning
