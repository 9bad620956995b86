#include "resolution/resolve_steps.hpp"

#include "collision/memory_budget.hpp"
#include "geometry/organ_mesh.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <cmath>
#include <stdexcept>

namespace canopy::resolving {
namespace {

/// The request's settings, refused before any work where resolution cannot run them. Said before
/// any round: resolution's working memory grows with the contacts it starts from.
const ResolveConfig& checked_config(const ResolveRequest& req, const Contacts& initial) {
  const ResolveConfig& cfg = req.config;
  cfg.check();
  if (cfg.level != ContactLevel::exact && cfg.level != ContactLevel::organ)
    throw std::invalid_argument("resolution detects at the exact or the organ level");
  if (initial.level != cfg.level)
    throw std::invalid_argument(fmt::format("resolution at the {} level was given contacts of the {} level",
                                            name_of(cfg.level), name_of(initial.level)));
  check_resolution_fits(initial.pairs.size(), req.detect.memory_limit);
  return cfg;
}

/// The detection a round repeats: the request's, at the resolution's level.
DetectRequest at_level(DetectRequest d, ContactLevel level) {
  d.level = level;
  return d;
}

}  // namespace

Resolution::Resolution(Stand& stand, DetectionBackend& backend, const ResolveRequest& req,
                       const Contacts& initial)
    : s(stand), backend(backend), req(req), cfg(checked_config(req, initial)),
      dreq(at_level(req.detect, cfg.level)), threads(dreq.threads > 0 ? dreq.threads : omp_get_max_threads()),
      joints(s, threads), boxes(fit_all()), near(s, boxes, threads),
      unbendable(s.organ_count(), 0), search{s,
                                             joints,
                                             lib,
                                             cfg,
                                             dreq.collide,
                                             near,
                                             boxes,
                                             touching,
                                             static_cast<float>(
                                                 std::max<double>(cfg.clearance, dreq.clearance)),
                                             dreq.clearance,
                                             &unbendable},
      contacts(initial.pairs), part(req.partition),
      left(static_cast<std::size_t>(total({owned_contacts()})[0])), carried(s.organ_count(), 0),
      moved_now(s.organ_count(), 0), best(left) {
  out.contacts_before = left;
  times.lap(PhaseTimes::setup);
}

std::vector<Obb, FirstTouchAllocator<Obb>> Resolution::fit_all() {
  make_meshes(s, lib, threads);
  std::vector<Obb, FirstTouchAllocator<Obb>> all(s.organ_count());
#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::size_t k = 0; k < s.organ_count(); ++k) all[k] = box_of(k);
  return all;
}

bool Resolution::stopped(int round) {
  if (left == 0) {
    out.converged = true;
    out.stop = "no contact left";
    return true;
  }
  if (round > cfg.max_rounds) {
    out.stop = fmt::format("round cap ({}) reached", cfg.max_rounds);
    return true;
  }
  if (left < best) best = left, best_round = round - 1;
  if (round - 1 - best_round >= cfg.stall_rounds) {
    out.stop = fmt::format("no progress in {} rounds (turns only trade contacts that cannot all be cleared)",
                           cfg.stall_rounds);
    return true;
  }
  return false;
}

Resolution::Round Resolution::prepare_round(int round) {
  if (req.progress) req.progress({round, left, now_seconds() - t0, left});
  Round w;
  w.record.round = round;
  w.record.contacts = left;
  w.started = now_seconds();
  times.lap(PhaseTimes::merge);  // the loop's own checks
  touching.build(s.organ_count(), contacts);
  // The runner of bulk attempts, if any (asked each round: it holds the stand as detected last),
  // told which organs moved since it last looked.
  AttemptSource* source = req.bulk_attempts ? attempt_source(backend) : nullptr;
  w.runner = req.attempts ? req.attempts : source ? source->attempt_runner(s) : nullptr;
  if (w.runner && req.statistics && w.runner != told) {
    // What the runner did before this resolution is not its work; from here on it keeps all.
    (void)w.runner->take_statistics();
    w.runner->keep_statistics(true);
  }
  if (w.runner) w.runner->update_organs(s, boxes, changed, w.runner != told), told = w.runner;
  // The witnesses serve the host's attempts, and a bulk scan's runner tests them first.
  if (cfg.level == ContactLevel::exact) touching.find_witnesses(s, lib, search.clearance, threads);
  times.lap(PhaseTimes::witnesses);
  return w;
}

bool Resolution::plan_turns(Round& w) {
  const int round = w.record.round;
  PlanRequest preq;
  preq.threads = threads;
  if (req.progress)
    preq.planning = [&](std::size_t pending) { req.progress({round, left, now_seconds() - t0, pending}); };
  preq.plan_plants = part ? &part->plan : nullptr;
  preq.runner = w.runner;
  if (const std::size_t lanes = w.runner ? std::min(req.bulk_lanes, w.runner->lanes()) : 1;
      lanes > 1 && !lane_threads)
    lane_threads.emplace(lanes);
  preq.lanes = w.runner && lane_threads ? &*lane_threads : nullptr;
  preq.batch_contacts = req.batch_contacts;
  preq.batch_organs = req.batch_organs;
  preq.host_carried = req.host_carried;
  preq.host_levels_below = req.host_levels_below;
  preq.pools = &pools;
  preq.tables = &tables;
  preq.lane_stats = req.statistics ? &lane_stats : nullptr;
  preq.ceiling = &ceiling;
  w.plan = plan_round(s, joints, contacts, touching, search, preq, times);
  ResolveRound& rr = w.record;
  // Asked after planning: a runner that fell back to the host half-way says so.
  rr.lanes = preq.lanes ? preq.lanes->lanes() : 1;
  rr.search = w.runner ? w.runner->hardware() : "host";
  rr.planning = w.runner ? fmt::format("{} attempts, {} lane{}", rr.search, rr.lanes, rr.lanes > 1 ? "s" : "")
                         : "host search";
  Plan& plan = w.plan;
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
  rr.plan_s = now_seconds() - w.started;
  // This process's own turns and marks (the halo's come from their owners below).
  w.counts =
      total({static_cast<std::int64_t>(plan.turns.size()),
             static_cast<std::int64_t>(std::count_if(plan.turns.begin(), plan.turns.end(),
                                                     [](const Turn& turn) { return turn.angle_deg >= 0; }))});
  if (w.counts[0] != 0) return true;
  out.stop = "no turn within the joint limits separates the contacts left";
  out.per_round.push_back(rr);
  return false;
}

void Resolution::apply_round(Round& w) {
  Plan& plan = w.plan;
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
  w.active.assign(s.plant_count(), 0);
  for (std::uint32_t k : moved) {
    const Affine3f& m = s.transforms[k];
    for (float v :
         {m.c0.x, m.c0.y, m.c0.z, m.c1.x, m.c1.y, m.c1.z, m.c2.x, m.c2.y, m.c2.z, m.t.x, m.t.y, m.t.z})
      if (!std::isfinite(v))
        throw std::logic_error(fmt::format("resolution made a non-finite transform for organ {}", k));
    carried[k] = 1;
    moved_now[k] = 1;
    w.active[static_cast<std::size_t>(s.organs[k].plant)] = 1;
  }
#pragma omp parallel for schedule(static, 1024) num_threads(threads)
  for (std::size_t i = 0; i < moved.size(); ++i) boxes[moved[i]] = box_of(moved[i]);
  near.update(s, boxes, w.active, threads);
  times.lap(PhaseTimes::refit);
}

void Resolution::detect_round(Round& w) {
  const std::vector<std::uint32_t>& moved = changed;
  w.started = now_seconds();
  dreq.active_plants = &w.active;
  dreq.moved_organs = &moved_now;
  Contacts again = backend.redetect(s, dreq, moved);
  times.lap(PhaseTimes::redetect);
  dreq.active_plants = nullptr;
  dreq.moved_organs = nullptr;
  w.record.detect_s = now_seconds() - w.started;
  // A backend may report unmoved pairs again: the same pair twice is one contact.
  std::erase_if(contacts, [&](const Contact& c) {
    return moved_now[static_cast<std::size_t>(c.organ_a)] || moved_now[static_cast<std::size_t>(c.organ_b)];
  });
  contacts.insert(contacts.end(), again.pairs.begin(), again.pairs.end());
  std::sort(contacts.begin(), contacts.end());
  contacts.erase(std::unique(contacts.begin(), contacts.end()), contacts.end());
  for (std::uint32_t k : moved) moved_now[k] = 0;
}

void Resolution::record_round(Round& w) {
  std::int64_t redetected = 0;
  for (std::size_t p = 0; p < w.active.size(); ++p)
    redetected += w.active[p] && mine(static_cast<std::int32_t>(p));
  const std::vector<std::int64_t> sums = total({owned_contacts(), redetected});
  left = static_cast<std::size_t>(sums[0]);
  w.record.turned = static_cast<std::size_t>(w.counts[1]);
  w.record.plants_redetected = static_cast<std::size_t>(sums[1]);
  out.per_round.push_back(w.record);
  out.rounds = w.record.round;
  why.clear();  // reasons belong to the list they were found on
}

ResolveStats Resolution::statistics() {
  ResolveStats st;
  st.collected = true;
  st.threads = threads;
  st.phases = times.phases();
  st.scan_busy_s = times.scan_busy;
  st.lanes = lane_stats;
  if (told) {
    st.attempts = told->take_statistics();
    told->keep_statistics(false);
  }
  return st;
}

}  // namespace canopy::resolving
