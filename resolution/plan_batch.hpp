#pragma once
/// The batches of one resolution round's planning (resolution/plan_round.hpp): a lane's state,
/// what the batches of a round share, and the planning of one batch of contacts (their
/// candidates scanned level by level, each contact taking the cheapest separating turn).
/// Internal to plan_round.cpp and plan_batch.cpp.
#include "resolution/batched_scan.hpp"
#include "resolution/plan_round.hpp"

#include <atomic>
#include <cstdint>
#include <mutex>
#include <optional>
#include <span>
#include <utility>
#include <vector>

namespace canopy::planning {

/// A lane: what it plans a batch with, and the batch's state (reused from batch to batch).
struct Lane {
  int threads = 1;
  std::vector<CandidatePool>* pools = nullptr;     // one per thread of the lane
  std::vector<ExactScratch>* scratches = nullptr;  // one per thread, for the host's search
  std::optional<BatchedScan> bulk;
  PhaseTimes* times = nullptr;
  std::vector<std::size_t> slots;       // the batch's movers (slots into the round's movers)
  std::vector<std::uint32_t> local_of;  // per mover of the round: its place among slots, or kNoPair
  std::vector<TurnSearch::Candidate*> state;
  // Per candidate: not made yet or still searching; wanted at this level; found by the runner
  // and refined on the host (the level where the host takes over).
  std::vector<std::uint8_t> open, want, handed;
  std::vector<std::optional<Turn>> refined;
  /// Seconds in batches, in the candidates' preparation, and levels run (PlanLaneStats).
  double batch_s = 0, prepare_s = 0;
  std::size_t levels = 0, host_levels = 0, handed_over = 0;
  std::array<std::size_t, PlanLaneStats::kLevelSizes> levels_by_size{};
  std::array<double, PlanLaneStats::kLevelSizes> seconds_by_size{};
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

}  // namespace canopy::planning
