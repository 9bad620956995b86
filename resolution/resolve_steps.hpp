#pragma once
/// The steps of resolve() (resolution/resolve.hpp) and the state they share from round to round:
/// resolve() is the loop `prepare_round, plan_turns, apply_round, detect_round, record_round`
/// until stopped(), then finish(). Internal to resolve.cpp and resolve_steps.cpp.
#include "resolution/attempt_batch.hpp"
#include "resolution/contact_graph.hpp"
#include "resolution/joints.hpp"
#include "resolution/lane_threads.hpp"
#include "resolution/neighbourhood.hpp"
#include "resolution/phase_times.hpp"
#include "resolution/plan_round.hpp"
#include "resolution/resolve.hpp"
#include "resolution/turn_search.hpp"
#include "geometry/clock.hpp"
#include "geometry/first_touch.hpp"
#include "geometry/obb.hpp"
#include "geometry/prototype.hpp"

#include <algorithm>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace canopy::resolving {

/// A resolution under way: what resolve()'s steps share from round to round. The constructor
/// sets it up (joints, meshes, boxes and neighbourhood of the stand as it is); each round then
/// prepares, plans, applies its turns, detects again and is recorded; finish() sums up.
struct Resolution {
  /// What one round's steps hand on to the next.
  struct Round {
    ResolveRound record;
    double started = 0;               // of the planning, then of the re-detection
    AttemptRunner* runner = nullptr;  // of bulk attempts, if any
    Plan plan;
    std::vector<std::int64_t> counts;  // over every process: turns and marks planned, joints turned
    std::vector<std::uint8_t> active;  // per plant: its organs moved this round
  };

  Resolution(Stand& stand, DetectionBackend& backend, const ResolveRequest& req, const Contacts& initial);

  /// Whether the loop ends before `round`, and why: no contact left, the round cap, or no
  /// progress for the stall rounds.
  bool stopped(int round);

  /// The round begun: the contact graph of the contacts left, the runner of bulk attempts (if
  /// any) told which organs moved since it last looked, and the witnesses found.
  Round prepare_round(int round);

  /// The round's turns, planned against the poses at its start, spread over their chains where
  /// they are large. False, with the loop's reason to stop, where no process planned any.
  bool plan_turns(Round& w);

  /// Every process's turns made (the halo's from their owners), the organs carried along posed
  /// anew, their boxes refit and the neighbourhood of their plants brought up to date.
  void apply_round(Round& w);

  /// The plants whose organs moved, and their neighbours, detected again; pairs with a moved
  /// organ take the new answer, the others keep theirs.
  void detect_round(Round& w);

  /// The round's record: the contacts left and the plants detected again over every process.
  void record_round(Round& w);

  /// What planned, the memory handed over, the contacts left with why, and the turns summed
  /// over every process.
  ResolveResult finish();
  /// ResolveResult::stats from the phase times, the lanes and the last runner (its counts taken).
  ResolveStats statistics();

  /// Organ k's OBB (no clearance) at its current transform.
  Obb box_of(std::size_t k) { return make_obb(s.transforms[k], lib.get(s.organs[k]).box, 0); }
  /// Every organ's mesh made and OBB fitted, written in full in parallel, which also faults the
  /// array's pages in.
  std::vector<Obb, FirstTouchAllocator<Obb>> fit_all();
  /// Whether this process owns `plant` (every plant without a partition).
  bool mine(std::int32_t plant) const { return !part || part->owned[static_cast<std::size_t>(plant)] != 0; }
  /// Sums over every process (this one alone without a partition).
  std::vector<std::int64_t> total(std::vector<std::int64_t> v) const {
    return part ? part->sum(std::move(v)) : v;
  }
  std::int64_t owned_contacts() const {
    return static_cast<std::int64_t>(
        std::count_if(contacts.begin(), contacts.end(), [&](const Contact& c) { return mine(c.plant_a); }));
  }

  // The state, made in this order by the constructor (the setup's order).
  Stand& s;
  DetectionBackend& backend;
  const ResolveRequest& req;
  const double t0 = now_seconds();
  PhaseTimes times{req.statistics};
  const ResolveConfig& cfg;
  ResolveResult out;
  DetectRequest dreq;
  const int threads;
  Joints joints;
  PrototypeLibrary lib;
  std::vector<Obb, FirstTouchAllocator<Obb>> boxes;
  Neighbourhood near;
  ContactGraph touching;
  std::vector<std::uint8_t> unbendable;
  const TurnSearch search;
  std::vector<Contact> contacts;
  const ResolvePartition* part;
  std::size_t left;
  std::vector<std::uint8_t> carried, moved_now;
  std::map<std::size_t, std::string> why;
  std::vector<std::uint32_t> changed;  // organs moved by the last round (the runner is told next round)
  std::vector<std::int64_t> bend_counts =
      std::vector<std::int64_t>(4, 0);  // this process's turns bent, their joints, kinks, unbent
  AttemptRunner* told = nullptr;        // the runner that has seen every organ
  std::size_t best;
  int best_round = 0;
  std::vector<std::vector<CandidatePool>> pools;  // per lane of planning, per thread
  std::vector<AttemptTables> tables;              // per lane of bulk planning
  std::optional<LaneThreads> lane_threads;        // made at the first round with a runner of several lanes
  std::vector<PlanLaneStats> lane_stats;          // per lane of planning (ResolveRequest::statistics)
  /// What resolution may hold, set as it starts (the memory limit, else what is available).
  const MemoryCeiling ceiling{req.detect.memory_limit};
};

}  // namespace canopy::resolving
