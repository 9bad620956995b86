#include "collision/plan_round.hpp"

#include "collision/batched_scan.hpp"
#include "collision/resolve_policy.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <mutex>
#include <optional>
#include <span>
#include <stdexcept>

namespace canopy {

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

/// A lane: what it plans a batch with, and the batch's state (reused from batch to batch).
struct Lane {
  int threads = 1;
  std::vector<CandidatePool>* pools = nullptr;     // one per thread of the lane
  std::vector<ExactScratch>* scratches = nullptr;  // the host's search (which has one lane)
  std::optional<BatchedScan> bulk;
  PhaseTimes* times = nullptr;
  std::vector<std::size_t> slots;       // the batch's movers (slots into the round's movers)
  std::vector<std::uint32_t> local_of;  // per mover of the round: its place among slots, or kNoPair
  std::vector<TurnSearch::Candidate*> state;
  std::vector<std::uint8_t> open, want;  // not made yet or still searching; wanted at this level
  std::vector<std::optional<Turn>> refined;
  /// With CANOPY_BULK_STATS: seconds in batches, in the candidates' preparation and levels run.
  double batch_s = 0, prepare_s = 0;
  std::size_t levels = 0;
};

/// (mover slot, turn) for each contact of a batch that picked one.
using Picks = std::vector<std::pair<std::size_t, Turn>>;

/// What the batches of a round share: the movers, each contact's candidates among them and
/// whether it has its turn.
struct Round {
  const Joints& joints;
  const ContactGraph& graph;
  const TurnSearch& search;
  const PlanRequest& request;
  const std::vector<std::uint32_t>& movers;
  const std::vector<std::vector<std::size_t>>& cand_slots;
  std::vector<std::uint8_t>& resolved;  // per contact; each batch writes its own
  std::atomic<std::size_t> unplanned{0};
  std::mutex progress{};

  /// Takes `done` contacts off the count still being planned and says so (one lane at a time).
  void tell(std::size_t done) {
    unplanned -= done;
    if (!request.planning) return;
    const std::lock_guard lock(progress);
    request.planning(unplanned.load());
  }
  Picks plan_batch(Lane& lane, std::span<const std::size_t> batch, bool strict);
};

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
    return std::span<const std::uint32_t>(cand_local.data() + local_first[q], local_first[q + 1] - local_first[q]);
  };
  std::vector<TurnSearch::Candidate*>& state = lane.state;
  std::vector<std::uint8_t>&open = lane.open, &want = lane.want;
  std::vector<std::optional<Turn>>& refined = lane.refined;
  state.assign(slots.size(), nullptr);
  open.assign(slots.size(), 1);
  want.assign(slots.size(), 0);
  refined.assign(slots.size(), std::nullopt);
  std::vector<CandidatePool>& pools = *lane.pools;
  for (CandidatePool& p : pools) p.used = 0;  // the last batch's candidates are free again
  if (lane.bulk) lane.bulk->clear();
  const double batch_start = PhaseTimes::now();
  std::vector<std::size_t> chosen;
  // Bulk: the candidates found at the last level, refined in this level's calls (with its scan).
  // Their contacts are settled (a contact with a candidate found is resolved, whatever the
  // refined angles), so they want no scan, and are picked once the refined turns are back: the
  // same contacts scanned at every level and the same picks, one level later.
  std::vector<std::size_t> unrefined;
  for (int level = 1; !pending.empty(); ++level) {
    ++lane.levels;
    tell(0);
    std::fill(want.begin(), want.end(), 0);
    for (std::size_t k : unrefined) want[k] = 2;
    for (std::uint32_t q : pending) {
      const std::span<const std::uint32_t> ks = candidates_of(q);
      if (std::any_of(ks.begin(), ks.end(), [&](std::uint32_t k) { return want[k] == 2; })) continue;  // settled
      for (std::uint32_t k : ks) want[k] |= open[k];
    }
    std::vector<std::size_t> scan;
    for (std::size_t k = 0; k < slots.size(); ++k)
      if (want[k] == 1) scan.push_back(k);
    if (scan.empty() && unrefined.empty()) break;
    // Neighbouring candidates (organs of one leaf) test against the same organs: a thread
    // that takes a few in a row finds their poses in its cache. Chunks of up to 8, fewer
    // where the level is short, so that no thread waits long at its end.
    const int chunk = static_cast<int>(std::clamp<std::size_t>(scan.size() / (16 * static_cast<std::size_t>(threads)), 1, 8));
    times.lap(PhaseTimes::bookkeeping);
    const double prepare_start = PhaseTimes::now();
#pragma omp parallel for schedule(dynamic, chunk) num_threads(threads)
    for (std::size_t j = 0; j < scan.size(); ++j) {
      const double started = times.on ? PhaseTimes::now() : 0;
      const std::size_t k = scan[j];
      const std::uint32_t m = movers[slots[k]];
      const auto me = static_cast<std::size_t>(omp_get_thread_num());
      if (!state[k]) state[k] = pools[me].take(), search.prepare(*state[k], m, contacts_of(joints, graph, m), strict);
      // Found: refined to its smallest turn at once, by the same thread (it depends on the
      // candidate alone).
      if (!lane.bulk && search.scan_level(*state[k], level, (*lane.scratches)[me]))
        refined[k] = search.refine(*state[k], (*lane.scratches)[me]);
      open[k] = state[k]->searching();
      if (times.on) {
        const double busy = PhaseTimes::now() - started;
#pragma omp atomic
        times.scan_busy += busy;
      }
    }
    lane.prepare_s += PhaseTimes::now() - prepare_start;
    const auto candidates = [&](const std::vector<std::size_t>& ks) {
      std::vector<TurnSearch::Candidate*> out;
      for (std::size_t k : ks) out.push_back(state[k]);
      return out;
    };
    if (lane.bulk) {
      // This level's scan, and the last level's finds each refined to its smallest turn, once.
      const std::vector<Turn> turns = lane.bulk->scan_and_refine(candidates(scan), level, candidates(unrefined));
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
      for (std::uint32_t k : candidates_of(q)) {
        if (!refined[k]) continue;
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
  }
  unplanned -= pending.size();  // left to the relaxed pass or the last resort
  lane.batch_s += PhaseTimes::now() - batch_start;
  Picks out;
  for (std::size_t k : chosen) out.emplace_back(slots[k], *refined[k]);
  return out;
}

}  // namespace

Plan plan_round(const Stand& s, const Joints& joints, const std::vector<Contact>& contacts, const ContactGraph& graph,
                const TurnSearch& search, const PlanRequest& req, PhaseTimes& times) {
  const ResolveConfig& cfg = search.config;
  const int threads = req.threads;
  const std::size_t n = contacts.size();
  std::vector<std::vector<std::uint32_t>> cands(n);
  std::vector<std::string> why(n);
  std::vector<std::uint32_t> movers;
  // Each contact's candidates on all threads (tens of thousands of contacts), then gathered.
#pragma omp parallel for schedule(dynamic, 512) num_threads(threads)
  for (std::size_t i = 0; i < n; ++i) {
    if (req.plan_plants && !(*req.plan_plants)[static_cast<std::size_t>(contacts[i].plant_a)] &&
        !(*req.plan_plants)[static_cast<std::size_t>(contacts[i].plant_b)])
      continue;  // known (its organs' neighbours need it) but decides no turn this process keeps
    cands[i] = candidate_movers(s, joints, contacts[i], cfg, why[i]);
    if (cands[i].size() > static_cast<std::size_t>(cfg.candidates)) cands[i].resize(static_cast<std::size_t>(cfg.candidates));
  }
  // The movers in organ order, and each one's slot among them: a mark per organ set on all
  // threads, then one pass over the marks (instead of sorting every contact's candidates).
  std::vector<std::uint8_t> is_mover(s.organ_count(), 0);
#pragma omp parallel for schedule(static, 512) num_threads(threads)
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint32_t m : cands[i]) std::atomic_ref<std::uint8_t>(is_mover[m]).store(1, std::memory_order_relaxed);
  const auto slot_of = std::make_unique_for_overwrite<std::uint32_t[]>(s.organ_count());  // read only where marked
  for (std::size_t k = 0; k < s.organ_count(); ++k)
    if (is_mover[k]) slot_of[k] = static_cast<std::uint32_t>(movers.size()), movers.push_back(static_cast<std::uint32_t>(k));
  const auto slot = [&](std::uint32_t m) { return static_cast<std::size_t>(slot_of[m]); };
  std::vector<std::vector<std::size_t>> cand_slots(n);
#pragma omp parallel for schedule(static, 512) num_threads(threads)
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint32_t m : cands[i]) cand_slots[i].push_back(slot(m));

  std::vector<std::optional<Turn>> turn_of(movers.size());
  times.lap(PhaseTimes::candidates);
  // One scratch per thread for the whole round: the poses it keeps stay valid while the stand
  // does not change, so they carry over from level to level.
  std::vector<ExactScratch> scratches(static_cast<std::size_t>(threads));
  std::vector<std::uint8_t> resolved(n, 0);
  Round round{joints, graph, search, req, movers, cand_slots, resolved};
  // The lanes: the first plans on this thread with the caller's pools and phase times; the
  // others (bulk attempts only) on threads of their own.
  const std::size_t n_lanes = req.runner && req.lanes ? req.lanes->lanes() : 1;
  if (req.runner && n_lanes > req.runner->lanes()) throw std::logic_error("planning: more lanes than the runner has");
  std::vector<std::vector<CandidatePool>>& pools = *req.pools;
  if (pools.size() < n_lanes) pools.resize(n_lanes);
  if (req.tables && req.tables->size() < n_lanes) req.tables->resize(n_lanes);
  PhaseTimes quiet;
  quiet.on = false;
  std::vector<Lane> lanes(n_lanes);
  for (std::size_t l = 0; l < n_lanes; ++l) {
    Lane& lane = lanes[l];
    // Every lane on all threads: a lane waiting for the device leaves its cores to the others
    // (4 lanes of 4 threads planned no faster on the 16-core H100 machine).
    lane.threads = threads;
    if (pools[l].size() < static_cast<std::size_t>(threads)) pools[l].resize(static_cast<std::size_t>(threads));
    lane.pools = &pools[l];
    lane.scratches = &scratches;
    if (req.runner) lane.bulk.emplace(search, *req.runner, threads, l, req.tables ? &(*req.tables)[l] : nullptr);
    lane.times = l == 0 ? &times : &quiet;
    lane.local_of.assign(movers.size(), kNoPair);
  }
  const std::size_t per_batch = std::max<std::size_t>(1, req.batch_contacts);
  for (bool strict : {true, false}) {
    std::vector<std::size_t> waiting;
    for (std::size_t i = 0; i < n; ++i)
      if (!resolved[i] && !cand_slots[i].empty()) waiting.push_back(i);
    round.unplanned = waiting.size();
    // Batches of at most batch_contacts, as many as a whole number of lanes takes, of one size.
    std::size_t batches = (waiting.size() + per_batch - 1) / per_batch;
    batches = (batches + n_lanes - 1) / n_lanes * n_lanes;
    const std::size_t size = batches ? std::max<std::size_t>(1, (waiting.size() + batches - 1) / batches) : 1;
    batches = (waiting.size() + size - 1) / size;
    const auto batch = [&](std::size_t b) {
      return std::span<const std::size_t>(waiting).subspan(b * size, std::min(size, waiting.size() - b * size));
    };
    std::vector<Picks> picks(batches);
    // Each lane takes the next batch not taken; any lane may plan any batch. A lane that fails
    // stops the others after their batch (LaneThreads::run rethrows its exception).
    std::atomic<std::size_t> next{0};
    const auto work = [&](std::size_t l) {
      try {
        for (std::size_t b; (b = next++) < batches;) picks[b] = round.plan_batch(lanes[l], batch(b), strict);
      } catch (...) {
        next = batches;
        throw;
      }
    };
    if (n_lanes > 1) req.lanes->run(work);
    else work(0);
    times.lap(PhaseTimes::scan);  // lane 0's wait for the others
    // In batch order (a mover picked in two batches made the same turn in both).
    for (const Picks& list : picks)
      for (const auto& [g, turn] : list)
        if (!turn_of[g]) turn_of[g] = turn;
  }
  if (std::getenv("CANOPY_BULK_STATS"))
    for (std::size_t l = 0; l < lanes.size(); ++l)
      fmt::print(stderr, "planning lane {}: {:.3f} s in batches, {} levels, candidates prepared in {:.3f} s\n", l, lanes[l].batch_s,
                 lanes[l].levels, lanes[l].prepare_s);
  lanes.clear();  // the batched scans print their statistics (CANOPY_BULK_STATS)
  // Last resort, contact by contact: a turn that clears this one contact, by a mover not yet
  // turning this round (the first contact to claim a mover keeps it).
  std::vector<std::size_t> left;
  for (std::size_t i = 0; i < n; ++i)
    if (!resolved[i] && !cand_slots[i].empty()) left.push_back(i);
  std::vector<std::optional<Turn>> alone(left.size());
#pragma omp parallel num_threads(threads)
  {
    ExactScratch& scratch = scratches[static_cast<std::size_t>(omp_get_thread_num())];
#pragma omp for schedule(dynamic, 1)
    for (std::size_t j = 0; j < left.size(); ++j) {
      const Contact& c = contacts[left[j]];
      const MetPairs met{{c.organ_a, c.organ_b}};
      std::vector<TurnSearch::Candidate> cs;
      for (std::size_t k : cand_slots[left[j]])
        if (!turn_of[k]) cs.push_back(search.prepare(movers[k], met, false));
      for (int level = 1; !alone[j]; ++level) {
        bool live = false;
        for (TurnSearch::Candidate& cand : cs) {
          live |= !cand.exhausted();
          if (search.scan_level(cand, level, scratch)) {
            alone[j] = search.refine(cand, scratch);
            break;
          }
        }
        if (!live) break;
      }
    }
  }
  times.lap(PhaseTimes::last_resort);
  for (std::size_t j = 0; j < left.size(); ++j) {
    if (!alone[j]) continue;
    std::optional<Turn>& slot_turn = turn_of[slot(alone[j]->organ)];
    if (!slot_turn) slot_turn = alone[j];
    resolved[left[j]] = 1;  // taken care of this round, or left to the next one by a claimed mover
  }

  Plan plan;
  for (std::size_t i = 0; i < n; ++i)
    if (!resolved[i])
      plan.why[i] = cands[i].empty() ? why[i]
                                     : fmt::format("no turn within the joint limits of the {} organ(s) tried separates them",
                                                   cands[i].size());
  for (const auto& t : turn_of)
    if (t) plan.turns.push_back(*t);
  return plan;
}

}  // namespace canopy
