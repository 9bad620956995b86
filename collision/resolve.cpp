#include "collision/resolve.hpp"

#include "collision/background_release.hpp"
#include "collision/memory_budget.hpp"
#include "collision/neighbourhood.hpp"
#include "collision/plan_round.hpp"
#include "collision/turn_search.hpp"
#include "geometry/clock.hpp"
#include "geometry/organ_mesh.hpp"
#include "geometry/first_touch.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>

namespace canopy {
ResolveResult resolve(Stand& s, DetectionBackend& backend, const ResolveRequest& req, const Contacts& initial) {
  const double t0 = now_seconds();
  PhaseTimes times;
  const ResolveConfig& cfg = req.config;
  cfg.check();
  if (cfg.level != ContactLevel::exact && cfg.level != ContactLevel::organ)
    throw std::invalid_argument("resolution detects at the exact or the organ level");
  if (initial.level != cfg.level)
    throw std::invalid_argument(fmt::format("resolution at the {} level was given contacts of the {} level", name_of(cfg.level),
                                            name_of(initial.level)));
  // Said before any round: resolution's working memory grows with the contacts it starts from.
  check_resolution_fits(initial.pairs.size(), req.detect.memory_limit);
  ResolveResult out;
  DetectRequest dreq = req.detect;
  dreq.level = cfg.level;
  const int threads = dreq.threads > 0 ? dreq.threads : omp_get_max_threads();
  Joints joints(s, threads);
  PrototypeLibrary lib;
  make_meshes(s, lib, threads);
  // Written in full by the parallel fit below, which also faults its pages in.
  std::vector<Obb, FirstTouchAllocator<Obb>> boxes(s.organ_count());
  const auto fit = [&](std::size_t k) {
    const OrganRecord& r = s.organs[k];
    boxes[k] = make_obb(s.transforms[k], lib.get(r).box, 0);
  };
#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::size_t k = 0; k < s.organ_count(); ++k) fit(k);
  Neighbourhood near(s, boxes, threads);
  ContactGraph touching;
  std::vector<std::uint8_t> unbendable(s.organ_count(), 0);
  const TurnSearch search{s, joints, lib, cfg, dreq.collide, near, boxes, touching,
                          static_cast<float>(std::max<double>(cfg.clearance, dreq.clearance)), dreq.clearance, &unbendable};

  std::vector<Contact> contacts = initial.pairs;
  const ResolvePartition* part = req.partition;
  const auto mine = [&](std::int32_t plant) { return !part || part->owned[static_cast<std::size_t>(plant)] != 0; };
  // Sums over every process (this one alone without a partition).
  const auto total = [&](std::vector<std::int64_t> v) { return part ? part->sum(std::move(v)) : v; };
  const auto owned_contacts = [&] {
    return static_cast<std::int64_t>(std::count_if(contacts.begin(), contacts.end(), [&](const Contact& c) { return mine(c.plant_a); }));
  };
  std::size_t left = static_cast<std::size_t>(total({owned_contacts()})[0]);
  out.contacts_before = left;
  std::vector<std::uint8_t> carried(s.organ_count(), 0), moved_now(s.organ_count(), 0);
  std::map<std::size_t, std::string> why;
  std::vector<std::uint32_t> changed;  // organs moved by the last round (the runner is told next round)
  std::vector<std::int64_t> bend_counts(4, 0);  // this process's turns bent, their joints, kinks, unbent
  const AttemptRunner* told = nullptr;  // the runner that has seen every organ
  std::size_t best = left;
  int best_round = 0;
  std::vector<std::vector<CandidatePool>> pools;  // per lane of planning, per thread
  std::vector<AttemptTables> tables;              // per lane of bulk planning
  std::optional<LaneThreads> lane_threads;         // made at the first round with a runner of several lanes
  times.lap(PhaseTimes::setup);
  for (int round = 1;; ++round) {
    if (left == 0) {
      out.converged = true;
      out.stop = "no contact left";
      break;
    }
    if (round > cfg.max_rounds) {
      out.stop = fmt::format("round cap ({}) reached", cfg.max_rounds);
      break;
    }
    if (left < best) best = left, best_round = round - 1;
    if (round - 1 - best_round >= cfg.stall_rounds) {
      out.stop = fmt::format("no progress in {} rounds (turns only trade contacts that cannot all be cleared)", cfg.stall_rounds);
      break;
    }
    if (req.progress) req.progress({round, left, now_seconds() - t0, left});
    ResolveRound rr;
    rr.round = round;
    rr.contacts = left;
    double t = now_seconds();
    times.lap(PhaseTimes::merge);  // the loop's own checks
    touching.build(s.organ_count(), contacts);
    // The runner of bulk attempts, if any (asked each round: it holds the stand as detected last),
    // told which organs moved since it last looked.
    AttemptSource* source = req.bulk_attempts ? attempt_source(backend) : nullptr;
    AttemptRunner* runner = req.attempts ? req.attempts : source ? source->attempt_runner(s) : nullptr;
    if (runner) runner->update_organs(s, boxes, changed, runner != told), told = runner;
    // The witnesses serve the host's attempts, and a bulk scan's runner tests them first.
    if (cfg.level == ContactLevel::exact) touching.find_witnesses(s, lib, search.clearance, threads);
    times.lap(PhaseTimes::witnesses);
    PlanRequest preq;
    preq.threads = threads;
    if (req.progress)
      preq.planning = [&](std::size_t pending) { req.progress({round, left, now_seconds() - t0, pending}); };
    preq.plan_plants = part ? &part->plan : nullptr;
    preq.runner = runner;
    if (const std::size_t lanes = runner ? std::min(req.bulk_lanes, runner->lanes()) : 1; lanes > 1 && !lane_threads)
      lane_threads.emplace(lanes);
    preq.lanes = runner && lane_threads ? &*lane_threads : nullptr;
    preq.batch_contacts = req.batch_contacts;
    preq.pools = &pools;
    preq.tables = &tables;
    Plan plan = plan_round(s, joints, contacts, touching, search, preq, times);
    // Asked after planning: a runner that fell back to the host half-way says so.
    rr.lanes = preq.lanes ? preq.lanes->lanes() : 1;
    rr.search = runner ? runner->hardware() : "host";
    rr.planning = runner ? fmt::format("{} attempts, {} lane{}", rr.search, rr.lanes, rr.lanes > 1 ? "s" : "") : "host search";
    why = std::move(plan.why);
    if (part)  // each process turns its own organs; the halo's turns come from their owners
      std::erase_if(plan.turns, [&](const Turn& turn) { return !mine(s.organs[turn.organ].plant); });
    // Large turns of chain segments bend their chains (within one plant: the owner's business).
    SpreadStats spread;
    plan.turns = spread_turns(search, plan.turns, threads, &spread);
    bend_counts[0] += spread.spread, bend_counts[1] += spread.joints, bend_counts[2] += spread.kinked;
    bend_counts[3] += static_cast<std::int64_t>(spread.unbent.size());
    // A mover no spread could take is searched within its own limit from now on; the mark travels
    // with the turns (an angle below 0, no turn) so that every process plans with it.
    for (std::uint32_t k : spread.unbent) plan.turns.push_back(Turn{k, Mat3d{}, -1});
    times.lap(PhaseTimes::apply);
    rr.plan_s = now_seconds() - t;
    // This process's own turns and marks (the halo's come from their owners below).
    const auto counts = total({static_cast<std::int64_t>(plan.turns.size()),
                               static_cast<std::int64_t>(std::count_if(plan.turns.begin(), plan.turns.end(),
                                                                       [](const Turn& turn) { return turn.angle_deg >= 0; }))});
    const auto planned = static_cast<std::size_t>(counts[0]);
    if (planned == 0) {
      out.stop = "no turn within the joint limits separates the contacts left";
      out.per_round.push_back(rr);
      break;
    }
    if (part) {
      const std::vector<Turn> halo = part->exchange(plan.turns);
      plan.turns.insert(plan.turns.end(), halo.begin(), halo.end());
    }
    std::vector<std::uint32_t> turned;
    for (const Turn& turn : plan.turns) {
      if (turn.angle_deg < 0) {
        unbendable[turn.organ] = 1;
        continue;
      }
      joints.set_local(turn.organ, turn.local);
      turned.push_back(turn.organ);
    }
    std::sort(turned.begin(), turned.end());
    changed = joints.update(s, turned, threads);
    times.lap(PhaseTimes::apply);
    const std::vector<std::uint32_t>& moved = changed;
    std::vector<std::uint8_t> active(s.plant_count(), 0);
    for (std::uint32_t k : moved) {
      const Affine3f& m = s.transforms[k];
      for (float v : {m.c0.x, m.c0.y, m.c0.z, m.c1.x, m.c1.y, m.c1.z, m.c2.x, m.c2.y, m.c2.z, m.t.x, m.t.y, m.t.z})
        if (!std::isfinite(v)) throw std::logic_error(fmt::format("resolution made a non-finite transform for organ {}", k));
      carried[k] = 1;
      moved_now[k] = 1;
      active[static_cast<std::size_t>(s.organs[k].plant)] = 1;
    }
#pragma omp parallel for schedule(static, 1024) num_threads(threads)
    for (std::size_t i = 0; i < moved.size(); ++i) fit(moved[i]);
    near.update(s, boxes, active, threads);
    times.lap(PhaseTimes::refit);
    t = now_seconds();
    dreq.active_plants = &active;
    dreq.moved_organs = &moved_now;
    Contacts again = backend.redetect(s, dreq, moved);
    times.lap(PhaseTimes::redetect);
    dreq.active_plants = nullptr;
    dreq.moved_organs = nullptr;
    rr.detect_s = now_seconds() - t;
    // Pairs with a moved organ take the new answer; the others keep theirs (a backend may report
    // them again: the same pair twice is one contact).
    std::erase_if(contacts, [&](const Contact& c) {
      return moved_now[static_cast<std::size_t>(c.organ_a)] || moved_now[static_cast<std::size_t>(c.organ_b)];
    });
    contacts.insert(contacts.end(), again.pairs.begin(), again.pairs.end());
    std::sort(contacts.begin(), contacts.end());
    contacts.erase(std::unique(contacts.begin(), contacts.end()), contacts.end());
    for (std::uint32_t k : moved) moved_now[k] = 0;
    std::int64_t redetected = 0;
    for (std::size_t p = 0; p < active.size(); ++p) redetected += active[p] && mine(static_cast<std::int32_t>(p));
    const std::vector<std::int64_t> sums = total({owned_contacts(), redetected});
    left = static_cast<std::size_t>(sums[0]);
    rr.turned = static_cast<std::size_t>(counts[1]);
    rr.plants_redetected = static_cast<std::size_t>(sums[1]);
    out.per_round.push_back(rr);
    out.rounds = round;
    why.clear();  // reasons belong to the list they were found on
  }
  times.lap(PhaseTimes::merge);
  // What planned, as it ran: each change between rounds said in order.
  const auto joined = [&](auto field) {
    std::string all;
    for (const ResolveRound& x : out.per_round)
      if (all.empty() || !all.ends_with(x.*field)) all += (all.empty() ? "" : "; then ") + x.*field;
    return all.empty() ? std::string("none") : all;
  };
  out.planning = joined(&ResolveRound::planning);
  out.search = joined(&ResolveRound::search);
  for (const ResolveRound& x : out.per_round) out.lanes = std::max(out.lanes, x.lanes);
  // The candidates and the lanes' tables go on a thread of their own (collision/
  // background_release.hpp), and the lanes' threads end: every turn is made, the caller goes on.
  lane_threads.reset();
  auto gone = std::make_shared<std::pair<std::vector<std::vector<CandidatePool>>, std::vector<AttemptTables>>>(std::move(pools),
                                                                                                           std::move(tables));
  BackgroundRelease::instance().hand_over([gone] { gone->first.clear(), gone->second.clear(); });
  times.lap(PhaseTimes::release);
  times.print(threads);
  out.contacts_after = left;
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    if (!mine(contacts[i].plant_a)) continue;
    const auto w = why.find(i);
    out.unresolved.push_back(
        {contacts[i], w != why.end() ? w->second : "still in contact when resolution stopped: " + out.stop});
  }
  // The mean turn as an exact sum of angles in units of 2^-32 degrees, so that it does not depend
  // on how the joints are split between processes.
  std::int64_t moved_joints = 0, angle_units = 0, owned_organs = 0, carried_organs = 0, owned_turned = 0;
  for (std::uint32_t k : joints.turned()) {
    if (!mine(s.organs[k].plant)) continue;
    ++owned_turned;
    const double a = joints.angle_deg(k);
    if (a <= 0) continue;
    ++moved_joints;
    angle_units += std::llround(std::ldexp(a, 32));
    out.max_joint_deg = std::max(out.max_joint_deg, a);
  }
  // The turn each organ carries: the rotation from its grown pose to its current one.
  for (std::size_t k = 0; k < s.organ_count(); ++k)
    if (carried[k] && mine(s.organs[k].plant))
      out.max_turn_deg = std::max(out.max_turn_deg, rotation_angle_deg(joints.motion(static_cast<std::uint32_t>(k)).r));
  for (std::size_t k = 0; k < s.organ_count(); ++k)
    if (mine(s.organs[k].plant)) ++owned_organs, carried_organs += carried[k];
  const std::vector<std::int64_t> sums = total({moved_joints, angle_units, owned_organs, carried_organs, owned_turned});
  if (part) out.max_turn_deg = part->max(out.max_turn_deg), out.max_joint_deg = part->max(out.max_joint_deg);
  out.organs_moved = static_cast<std::size_t>(sums[0]);
  if (out.organs_moved) out.mean_turn_deg = std::ldexp(static_cast<double>(sums[1]), -32) / static_cast<double>(out.organs_moved);
  out.organs_carried = static_cast<std::size_t>(sums[3]);
  const std::vector<std::int64_t> bent = total(bend_counts);
  out.bends = static_cast<std::size_t>(bent[0]), out.bend_joints = static_cast<std::size_t>(bent[1]);
  out.kinks = static_cast<std::size_t>(bent[2]), out.unbent = static_cast<std::size_t>(bent[3]);
  out.joint_bytes = Joints::bytes_for(static_cast<std::size_t>(sums[2]), static_cast<std::size_t>(sums[4]));
  out.seconds = now_seconds() - t0;
  return out;
}

}  // namespace canopy
