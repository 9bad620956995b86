#pragma once
/// One round of resolution's planning (resolution/resolve.hpp): every contact's candidate movers
/// scanned level by level of cost, in batches of contacts, each contact taking the cheapest
/// separating turn among its candidates. With a runner of bulk attempts (resolution/
/// batched_scan.hpp) that has several lanes, several batches are planned at once, one per lane
/// on a thread of its own (resolution/lane_threads.hpp): while one lane waits for the device,
/// another does its host work.
/// Batches are independent (a contact's pick depends only on its own candidates' scans) and
/// their turns are merged in batch order, so the plan is the same for any number of lanes.
#include "collision/memory_budget.hpp"
#include "resolution/attempt_batch.hpp"
#include "collision/contacts.hpp"
#include "resolution/joints.hpp"
#include "resolution/lane_threads.hpp"
#include "resolution/phase_times.hpp"
#include "resolution/resolve_stats.hpp"
#include "resolution/turn_search.hpp"

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace canopy {

/// The candidates of a batch come from a pool per thread, whose lists keep their memory from
/// batch to batch and round to round: made, recycled and reused by the thread that took them,
/// let go only when resolution ends (letting tens of thousands of candidates go after each
/// batch costs the planning time: bench_resolve at 10,000 plants on a GPU, about 10 %).
struct alignas(64) CandidatePool {  // one per thread, side by side: a cache line each
  std::vector<std::unique_ptr<TurnSearch::Candidate>> owned;
  std::size_t used = 0;
  TurnSearch::Candidate* take() {
    if (used == owned.size()) owned.push_back(std::make_unique<TurnSearch::Candidate>());
    return owned[used++].get();
  }
};

struct Plan {
  std::vector<Turn> turns;                 // by organ id
  std::map<std::size_t, std::string> why;  // contacts no turn took care of, by index
};

/// Contacts per batch of planning by default (ResolveRequest::batch_contacts says why this many).
inline constexpr std::size_t kDefaultBatchContacts = 16384;
/// Organs carried by a batch's candidates at most by default (ResolveRequest::batch_organs says why).
inline constexpr std::size_t kDefaultBatchOrgans = std::size_t{8} << 20;
/// A batch whose candidate movers carry more organs than this each on average is searched on the
/// host (resolution/plan_batch.cpp says why); the default tomato's carry 8 on average, the mature one's 13.
inline constexpr std::size_t kHostCarriedPerCandidate = 256;
/// Levels smaller than this go to the host's search by default (ResolveRequest::host_levels_below).
inline constexpr std::size_t kDefaultHostLevelsBelow = 64;

struct PlanRequest {
  int threads = 1;
  /// Called as planning goes on with the number of contacts still without a turn, when set.
  std::function<void(std::size_t)> planning;
  /// Per plant: whether its contacts decide turns here (tiles; null: all of them).
  const std::vector<std::uint8_t>* plan_plants = nullptr;
  /// Bulk attempts through this runner when set (else the host's candidate-by-candidate search).
  AttemptRunner* runner = nullptr;
  /// Batches planned at once with a runner, one per lane of these (lane 0 the caller's; null:
  /// one at a time). At most the runner's lanes.
  LaneThreads* lanes = nullptr;
  std::size_t batch_contacts = kDefaultBatchContacts;       // contacts per batch
  std::size_t batch_organs = kDefaultBatchOrgans;           // ResolveRequest::batch_organs
  std::size_t host_levels_below = kDefaultHostLevelsBelow;  // ResolveRequest::host_levels_below
  std::size_t host_carried = kHostCarriedPerCandidate;      // ResolveRequest::host_carried
  /// Per lane, one pool per thread (grown here; kept by the caller from round to round).
  std::vector<std::vector<CandidatePool>>* pools = nullptr;
  /// Per lane, the batched scan's tables (grown here; kept by the caller from round to round,
  /// null: made anew each round).
  std::vector<AttemptTables>* tables = nullptr;
  /// Per lane, where the round's time went, added to (grown here; ResolveRequest::statistics).
  std::vector<PlanLaneStats>* lane_stats = nullptr;
  /// Checked as candidates are prepared (null: none): past it the round stops with an error.
  const MemoryCeiling* ceiling = nullptr;
};

/// One round's turns, all planned against the poses at the start of the round. Each contact
/// takes the cheapest turn among its first candidate movers, each mover asked to separate every
/// contact its subtree has (so a mover picked by several contacts makes one turn). Movers are
/// scanned level by level of cost, in parallel, each mover once per level whichever contacts
/// ask for it; a strict pass (no new contacts) comes first, a relaxed pass takes what is left.
Plan plan_round(const Stand& stand, const Joints& joints, const std::vector<Contact>& contacts,
                const ContactGraph& graph, const TurnSearch& search, const PlanRequest& request,
                PhaseTimes& times);

}  // namespace canopy
