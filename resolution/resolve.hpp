#pragma once
/// Collision resolution (the paper's §3.5 feedback, taken to a fixed point): the contacts found
/// are fed back into the stand by turning offending organs about their joints (never scaling,
/// moving or removing them), rounds of refit + re-detection of the plants that moved and their
/// neighbours, until detection finds no contact or the round cap is hit. Every round plans all
/// its turns against the poses at the start of the round (in parallel, the same for any thread
/// count), then applies them together; several contacts on one organ make one combined turn.
#include "resolution/attempt_batch.hpp"
#include "resolution/attempt_source.hpp"
#include "resolution/bend_spread.hpp"
#include "collision/backend.hpp"
#include "resolution/joints.hpp"
#include "resolution/plan_round.hpp"
#include "resolution/resolve_policy.hpp"
#include "resolution/resolve_stats.hpp"
#include "resolution/turn_search.hpp"

#include <functional>
#include <string>
#include <vector>

namespace canopy {

struct ResolveProgress {
  int round = 0;
  std::size_t contacts = 0;   // left at the start of the round
  double seconds = 0;         // since resolution began
  std::size_t unplanned = 0;  // contacts of the round still without a turn (planning goes on)
};

/// Resolution over tiles (distributed/): this process holds the plants it owns plus a halo deep
/// enough that every turn of an owned organ is planned exactly as in one process; the loop's
/// decisions use the sums over every process, and each round the turns are traded so that halo
/// plants move as their owners moved them.
struct ResolvePartition {
  std::vector<std::uint8_t> owned;  // per local plant
  /// Per local plant: whether its contacts are planned here. A process's own turns are decided by
  /// the contacts of the plants within one hop of its own (the picks among their candidates, the
  /// movers they claim); contacts farther out only need to be known.
  std::vector<std::uint8_t> plan;
  /// Element-wise sums over every process.
  std::function<std::vector<std::int64_t>(std::vector<std::int64_t>)> sum;
  std::function<double(double)> max;
  /// Takes this process's turns of its own organs, returns the turns other processes made on
  /// this process's halo organs (local organ ids both ways).
  std::function<std::vector<Turn>(const std::vector<Turn>&)> exchange;
};

struct ResolveRequest {
  DetectRequest detect;  // its level is replaced by config.level
  ResolveConfig config;
  /// Null: this process holds the whole stand. Otherwise every number in the result is the
  /// whole stand's, except `unresolved`, which lists the contacts this process owns.
  const ResolvePartition* partition = nullptr;
  /// Called at the start of each round and as its planning goes on (by cost level), when set.
  std::function<void(const ResolveProgress&)> progress;
  /// Runs each level's turn-search attempts in bulk (resolution/batched_scan.hpp) through this
  /// runner when set. The turns are the same either way.
  AttemptRunner* attempts = nullptr;
  /// True (and `attempts` null): through the backend's runner where it has one (its
  /// AttemptSource, resolution/attempt_source.hpp; CUDA: on the device, in lanes); the CPU backend
  /// has none and searches candidate by candidate. False: the host's search on any backend. On a
  /// 16-core GPU machine the device's lanes resolve a 10,000-plant stand faster than the host's
  /// search (bench_resolve: about 2x).
  bool bulk_attempts = true;
  /// Batches of contacts planned at once through the runner, each on a lane of its own (at most
  /// the runner's lanes): one lane's host work overlaps another's device work. The turns are the
  /// same for any number (resolution/plan_round.hpp). 6: faster than 4 on 16-core GPU machines
  /// (bench_resolve at 10,000 plants, alternated runs).
  std::size_t bulk_lanes = 6;
  /// Contacts per batch of planning: the search state held at once stays bounded whatever the
  /// stand's size; the turns do not depend on it. Batches come in whole multiples of the lanes,
  /// of one size, so 16,384 gives each of 6 lanes one batch of a 10,000-plant stand's 73,936
  /// contacts: fewer levels one after another per lane than two batches each (8,192; faster on a
  /// GPU, bench_resolve at 10,000 plants), for more memory at the peak on the CPU backend (8 %).
  std::size_t batch_contacts = kDefaultBatchContacts;
  /// A batch is split further where its contacts' candidate movers carry more organs than this
  /// in all (each candidate holds its subtree's organs and their pairs): a plant whose turning
  /// organs carry long chains (a 2,000-segment chain: 7,697 contacts of 14 candidates, most
  /// carrying about 1,000 organs) held 1.38 GB of candidates at once in one batch, past which
  /// memory ran out. 8 Mi organs: the default stands' batches (1.7 M at 10,000 plants) stay whole.
  /// The turns do not depend on it.
  std::size_t batch_organs = kDefaultBatchOrgans;
  /// With bulk attempts: a level of a batch that scans and refines fewer candidates than this is
  /// searched by the host's threads instead (and every later level of the batch: they only get
  /// smaller). The tail of a batch, a few candidates that keep failing up to their reach, costs
  /// a runner a round trip or two per level whatever its size; the turns are the same either way.
  std::size_t host_levels_below = kDefaultHostLevelsBelow;
  /// With bulk attempts: a batch whose candidate movers carry more organs than this each on
  /// average (long chains) is searched on the host's threads throughout (resolution/plan_batch.cpp);
  /// the turns are the same either way.
  std::size_t host_carried = kHostCarriedPerCandidate;
  /// Collect ResolveResult::stats: where the time went phase by phase (wall, CPU, page faults),
  /// lane by lane of planning, and what the runner of bulk attempts did (on the device, with a
  /// pair of events around every kernel). Off: none of it is measured; the turns are the same.
  bool statistics = false;
};

struct ResolveRound {
  int round = 0;
  std::size_t contacts = 0;  // at the start of the round
  std::size_t turned = 0;    // joints turned in the round
  std::size_t plants_redetected = 0;
  double plan_s = 0, detect_s = 0;
  /// What planned the round, as it ran: "host search" (candidate by candidate on the host's
  /// cores) or "<hardware> attempts, N lanes" (a runner's bulk attempts, the device's on CUDA);
  /// `search` is "host" or the runner's hardware, `lanes` the batches planned at once.
  std::string planning, search;
  std::size_t lanes = 0;
};

struct UnresolvedContact {
  Contact contact;
  std::string reason;
};

struct ResolveResult {
  std::size_t contacts_before = 0, contacts_after = 0;  // at config.level
  int rounds = 0;                                       // rounds that turned organs
  bool converged = false;                               // no contact left
  std::string stop;                                     // why the loop ended
  std::size_t organs_moved = 0;                         // joints turned (organs carried along not counted)
  std::size_t organs_carried = 0;                       // organs whose transform changed
  /// The mean of the turned joints' final angles; the largest turn an organ carries from its
  /// grown orientation (a bent chain's whole bend, a kink's joint angle); the largest single
  /// joint angle.
  double mean_turn_deg = 0, max_turn_deg = 0, max_joint_deg = 0;
  /// Turns spread over several joints of their chain, the joints they became, turns above the
  /// bend step left at one joint, and turns past their joint's own limit that no spread could
  /// take (not made) (resolution/bend_spread.hpp), over every round.
  std::size_t bends = 0, bend_joints = 0, kinks = 0, unbent = 0;
  std::vector<ResolveRound> per_round;
  std::vector<UnresolvedContact> unresolved;  // what is left, with why
  std::size_t joint_bytes = 0;
  /// How the rounds were planned, as they ran (never what was asked): the rounds' `planning`,
  /// and `search` ("device" or "host"), joined with "; then " where they changed between rounds
  /// (a backend that fell back to the CPU); "none" when no round was planned. `lanes`: the most
  /// batches any round planned at once (0 with no round).
  std::string planning = "none", search = "none";
  std::size_t lanes = 0;
  double seconds = 0;
  /// Where the time went, with ResolveRequest::statistics (`collected` false otherwise): this
  /// process's own, over tiles too.
  ResolveStats stats;
};

/// Resolves `stand` in place. `initial` holds the contacts at config.level that
/// `backend.detect(stand, ...)` has just found (the backend keeps its tree for the rounds).
ResolveResult resolve(Stand& stand, DetectionBackend& backend, const ResolveRequest& request,
                      const Contacts& initial);

}  // namespace canopy
