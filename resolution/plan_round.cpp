#include "resolution/plan_round.hpp"

#include "resolution/plan_batch.hpp"
#include "resolution/resolve_policy.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <optional>
#include <span>
#include <stdexcept>

namespace canopy {

using planning::Lane;
using planning::Picks;
using planning::Round;

Plan plan_round(const Stand& s, const Joints& joints, const std::vector<Contact>& contacts,
                const ContactGraph& graph, const TurnSearch& search, const PlanRequest& req,
                PhaseTimes& times) {
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
    if (cands[i].size() > static_cast<std::size_t>(cfg.candidates))
      cands[i].resize(static_cast<std::size_t>(cfg.candidates));
  }
  // The movers in organ order, and each one's slot among them: a mark per organ set on all
  // threads, then one pass over the marks (instead of sorting every contact's candidates).
  std::vector<std::uint8_t> is_mover(s.organ_count(), 0);
#pragma omp parallel for schedule(static, 512) num_threads(threads)
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint32_t m : cands[i])
      std::atomic_ref<std::uint8_t>(is_mover[m]).store(1, std::memory_order_relaxed);
  const auto slot_of =
      std::make_unique_for_overwrite<std::uint32_t[]>(s.organ_count());  // read only where marked
  for (std::size_t k = 0; k < s.organ_count(); ++k)
    if (is_mover[k])
      slot_of[k] = static_cast<std::uint32_t>(movers.size()), movers.push_back(static_cast<std::uint32_t>(k));
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
  if (req.runner && n_lanes > req.runner->lanes())
    throw std::logic_error("planning: more lanes than the runner has");
  std::vector<std::vector<CandidatePool>>& pools = *req.pools;
  if (pools.size() < n_lanes) pools.resize(n_lanes);
  if (req.tables && req.tables->size() < n_lanes) req.tables->resize(n_lanes);
  PhaseTimes quiet;
  std::vector<Lane> lanes(n_lanes);
  // The other lanes' own scratches, for the levels they search on the host (a lane's threads
  // number theirs from 0, as lane 0's do).
  std::vector<std::vector<ExactScratch>> lane_scratches(n_lanes - 1);
  for (std::size_t l = 0; l < n_lanes; ++l) {
    Lane& lane = lanes[l];
    // Every lane on all threads: a lane waiting for the device leaves its cores to the others
    // (4 lanes of 4 threads each plan no faster on a 16-core GPU machine).
    lane.threads = threads;
    if (pools[l].size() < static_cast<std::size_t>(threads))
      pools[l].resize(static_cast<std::size_t>(threads));
    lane.pools = &pools[l];
    if (l > 0) lane_scratches[l - 1].resize(static_cast<std::size_t>(threads));
    lane.scratches = l == 0 ? &scratches : &lane_scratches[l - 1];
    if (req.runner)
      lane.bulk.emplace(search, *req.runner, threads, l, req.tables ? &(*req.tables)[l] : nullptr);
    lane.times = l == 0 ? &times : &quiet;
    lane.local_of.assign(movers.size(), kNoPair);
  }
  const std::size_t per_batch = std::max<std::size_t>(1, req.batch_contacts);
  for (bool strict : {true, false}) {
    std::vector<std::size_t> waiting;
    for (std::size_t i = 0; i < n; ++i)
      if (!resolved[i] && !cand_slots[i].empty()) waiting.push_back(i);
    round.unplanned = waiting.size();
    // Batches of at most batch_contacts, as many as a whole number of lanes takes, of one size;
    // each split again where its candidates carry more than batch_organs organs in all.
    std::size_t batches = (waiting.size() + per_batch - 1) / per_batch;
    batches = (batches + n_lanes - 1) / n_lanes * n_lanes;
    const std::size_t size = batches ? std::max<std::size_t>(1, (waiting.size() + batches - 1) / batches) : 1;
    std::vector<std::size_t> bounds{0};
    for (std::size_t from = 0; from < waiting.size(); from += size) {
      const std::size_t to = std::min(waiting.size(), from + size);
      std::size_t carried = 0;
      for (std::size_t i = from; i < to; ++i) {
        std::size_t c = 0;
        for (std::size_t g : cand_slots[waiting[i]]) c += joints.subtree_end(movers[g]) - movers[g];
        if (carried > 0 && carried + c > req.batch_organs) bounds.push_back(i), carried = 0;
        carried += c;
      }
      bounds.push_back(to);
    }
    batches = bounds.size() - 1;
    const auto batch = [&](std::size_t b) {
      return std::span<const std::size_t>(waiting).subspan(bounds[b], bounds[b + 1] - bounds[b]);
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
  if (req.lane_stats) {
    if (req.lane_stats->size() < lanes.size()) req.lane_stats->resize(lanes.size());
    for (std::size_t l = 0; l < lanes.size(); ++l) {
      PlanLaneStats& to = (*req.lane_stats)[l];
      to.batch_s += lanes[l].batch_s, to.prepare_s += lanes[l].prepare_s, to.levels += lanes[l].levels;
      to.host_levels += lanes[l].host_levels, to.handed_over += lanes[l].handed_over;
      for (std::size_t k = 0; k < PlanLaneStats::kLevelSizes; ++k) {
        to.levels_by_size[k] += lanes[l].levels_by_size[k];
        to.seconds_by_size[k] += lanes[l].seconds_by_size[k];
      }
      if (lanes[l].bulk) lanes[l].bulk->add_stats(to);
    }
  }
  lanes.clear();
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
      plan.why[i] =
          cands[i].empty()
              ? why[i]
              : fmt::format("no turn within the joint limits of the {} organ(s) tried separates them",
                            cands[i].size());
  for (const auto& t : turn_of)
    if (t) plan.turns.push_back(*t);
  return plan;
}

}  // namespace canopy
