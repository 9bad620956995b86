#include "collision/resolve.hpp"

#include "collision/batched_scan.hpp"
#include "collision/neighbourhood.hpp"
#include "collision/turn_search.hpp"
#include "geometry/organ_mesh.hpp"
#include "geometry/first_touch.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>

namespace canopy {
namespace {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

/// Where resolution's time goes, phase by phase over all rounds, printed at its end when
/// CANOPY_PLAN_STATS is set (off: one branch per phase); `scan_busy` sums the candidates'
/// scan times over the threads, so scan_busy / (threads x scan) is the scan's parallel share.
struct PhaseTimes {
  enum Phase { setup, witnesses, candidates, bookkeeping, scan, pick, last_resort, apply, refit, redetect, merge, release, count };
  bool on = std::getenv("CANOPY_PLAN_STATS") != nullptr;
  double seconds[count] = {}, scan_busy = 0, mark = now();
  void lap(Phase p) {
    if (!on) return;
    const double t = now();
    seconds[p] += t - mark, mark = t;
  }
  void print(int threads) const {
    if (!on) return;
    static constexpr const char* names[count] = {"setup", "witnesses", "candidates", "bookkeeping", "scan", "pick",
                                                 "last resort", "apply turns", "refit", "redetect", "merge", "release"};
    std::string line = "resolution phases (s):";
    for (int p = 0; p < count; ++p) line += fmt::format(" {} {:.3f},", names[p], seconds[p]);
    fmt::print(stderr, "{} scan busy {:.2f} thread-s on {} threads\n", line, scan_busy, threads);
  }
};

struct Plan {
  std::vector<Turn> turns;                   // by organ id
  std::map<std::size_t, std::string> why;    // contacts no turn took care of, by index
};

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

/// The candidates of a batch come from a pool per thread, whose lists keep their memory from
/// batch to batch and round to round: made, recycled and reused by the thread that took them,
/// let go only when resolution ends (10,000 plants on the H200 machine's 16 threads: letting
/// tens of thousands of candidates go after each batch cost about 0.2 s of 1.9 s of planning).
struct alignas(64) CandidatePool {  // one per thread, side by side: a cache line each
  std::vector<std::unique_ptr<TurnSearch::Candidate>> owned;
  std::size_t used = 0;
  TurnSearch::Candidate* take() {
    if (used == owned.size()) owned.push_back(std::make_unique<TurnSearch::Candidate>());
    return owned[used++].get();
  }
};

/// One round's turns, all planned against the poses at the start of the round. Each contact
/// takes the cheapest turn among its first candidate movers, each mover asked to separate every
/// contact its subtree has (so a mover picked by several contacts makes one turn). Movers are
/// scanned level by level of cost, in parallel, each mover once per level whichever contacts
/// ask for it; a strict pass (no new contacts) comes first, a relaxed pass takes what is left.
Plan plan_round(const Stand& s, const Joints& joints, const std::vector<Contact>& contacts, const ContactGraph& graph,
                const TurnSearch& search, int threads, const std::function<void(std::size_t)>& planning,
                const std::vector<std::uint8_t>* plan_plants, AttemptRunner* runner, std::vector<CandidatePool>& pools,
                PhaseTimes& times) {
  const ResolveConfig& cfg = search.config;
  const std::size_t n = contacts.size();
  std::vector<std::vector<std::uint32_t>> cands(n);
  std::vector<std::string> why(n);
  std::vector<std::uint32_t> movers;
  // Each contact's candidates on all threads (tens of thousands of contacts), then gathered.
#pragma omp parallel for schedule(dynamic, 512) num_threads(threads)
  for (std::size_t i = 0; i < n; ++i) {
    if (plan_plants && !(*plan_plants)[static_cast<std::size_t>(contacts[i].plant_a)] &&
        !(*plan_plants)[static_cast<std::size_t>(contacts[i].plant_b)])
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
  std::optional<BatchedScan> bulk;
  if (runner) bulk.emplace(search, *runner, threads);
  // Contacts are planned in batches: a contact's pick depends only on its own candidates' scans
  // (each candidate is scanned at every level while any contact wanting it is pending), so a
  // batch gives the same turns as the whole list, and the search state held at once stays
  // bounded whatever the stand's size.
  constexpr std::size_t kBatch = 8192;
  // Per batch, reused: its movers (slots into `movers`), where each sits among them (kNoPair:
  // not in the batch), their search state, whether each is still open (not made yet, or neither
  // found nor exhausted), wanted at this level, and refined.
  std::vector<std::size_t> slots;
  std::vector<std::uint32_t> local_of(movers.size(), kNoPair);
  std::vector<TurnSearch::Candidate*> state;
  std::vector<std::uint8_t> open, want;
  std::vector<std::optional<Turn>> refined;
  for (bool strict : {true, false}) {
    std::vector<std::size_t> waiting;
    for (std::size_t i = 0; i < n; ++i)
      if (!resolved[i] && !cand_slots[i].empty()) waiting.push_back(i);
    for (std::size_t b0 = 0; b0 < waiting.size(); b0 += kBatch) {
      const std::size_t b1 = std::min(waiting.size(), b0 + kBatch);
      slots.clear();
      for (std::size_t q = b0; q < b1; ++q)
        for (std::size_t g : cand_slots[waiting[q]])
          if (local_of[g] == kNoPair) local_of[g] = 0, slots.push_back(g);
      std::sort(slots.begin(), slots.end());
      for (std::size_t k = 0; k < slots.size(); ++k) local_of[slots[k]] = static_cast<std::uint32_t>(k);
      // Each contact's candidates as indices into the batch's movers, found once: those of
      // waiting[b0 + q] are cand_local[local_first[q], local_first[q + 1]). Pending: values of q.
      std::vector<std::uint32_t> local_first{0}, cand_local, pending;
      for (std::size_t q = b0; q < b1; ++q) {
        pending.push_back(static_cast<std::uint32_t>(q - b0));
        for (std::size_t g : cand_slots[waiting[q]]) cand_local.push_back(local_of[g]);
        local_first.push_back(static_cast<std::uint32_t>(cand_local.size()));
      }
      for (std::size_t g : slots) local_of[g] = kNoPair;
      const auto candidates_of = [&](std::uint32_t q) {
        return std::span<const std::uint32_t>(cand_local.data() + local_first[q], local_first[q + 1] - local_first[q]);
      };
      state.assign(slots.size(), nullptr);
      open.assign(slots.size(), 1);
      want.assign(slots.size(), 0);
      refined.assign(slots.size(), std::nullopt);
      for (CandidatePool& p : pools) p.used = 0;  // the last batch's candidates are free again
      if (bulk) bulk->clear();
      std::vector<std::size_t> chosen;
      for (int level = 1; !pending.empty(); ++level) {
        if (planning) planning(pending.size() + (waiting.size() - b1));  // this batch's + later ones
        std::fill(want.begin(), want.end(), 0);
        for (std::uint32_t q : pending)
          for (std::uint32_t k : candidates_of(q)) want[k] |= open[k];
        std::vector<std::size_t> scan;
        for (std::size_t k = 0; k < slots.size(); ++k)
          if (want[k]) scan.push_back(k);
        if (scan.empty()) break;
        // Neighbouring candidates (organs of one leaf) test against the same organs: a thread
        // that takes a few in a row finds their poses in its cache. Chunks of up to 8, fewer
        // where the level is short, so that no thread waits long at its end.
        const int chunk = static_cast<int>(std::clamp<std::size_t>(scan.size() / (16 * static_cast<std::size_t>(threads)), 1, 8));
        times.lap(PhaseTimes::bookkeeping);
#pragma omp parallel for schedule(dynamic, chunk) num_threads(threads)
        for (std::size_t j = 0; j < scan.size(); ++j) {
          const double started = times.on ? now() : 0;
          const std::size_t k = scan[j];
          const std::uint32_t m = movers[slots[k]];
          const auto me = static_cast<std::size_t>(omp_get_thread_num());
          if (!state[k]) state[k] = pools[me].take(), search.prepare(*state[k], m, contacts_of(joints, graph, m), strict);
          // Found: refined to its smallest turn at once, by the same thread (it depends on the
          // candidate alone).
          if (!bulk && search.scan_level(*state[k], level, scratches[me])) refined[k] = search.refine(*state[k], scratches[me]);
          open[k] = state[k]->searching();
          if (times.on) {
            const double busy = now() - started;
#pragma omp atomic
            times.scan_busy += busy;
          }
        }
        const auto candidates = [&](const std::vector<std::size_t>& ks) {
          std::vector<TurnSearch::Candidate*> out;
          for (std::size_t k : ks) out.push_back(state[k]);
          return out;
        };
        if (bulk) {
          bulk->scan(candidates(scan), level);
          // Candidates found at this level: each refined to its smallest turn, once.
          std::vector<std::size_t> found;
          for (std::size_t k : scan)
            if (state[k]->found_axis >= 0 && !refined[k]) found.push_back(k);
          const std::vector<Turn> turns = bulk->refine(candidates(found));
          for (std::size_t j = 0; j < found.size(); ++j) refined[found[j]] = turns[j];
          for (std::size_t k : scan) open[k] = state[k]->searching();
        }
        times.lap(PhaseTimes::scan);  // with the batched scan's own work
        // Each contact with a candidate found takes the cheapest (angle x weight; ties: policy order).
        std::erase_if(pending, [&](std::uint32_t q) {
          const std::size_t i = waiting[b0 + q];
          std::optional<std::size_t> pick;
          double cost = 0;
          for (std::uint32_t k : candidates_of(q)) {
            if (!refined[k]) continue;
            const double c = refined[k]->angle_deg * state[k]->weight;
            if (!pick || c < cost) pick = k, cost = c;
          }
          if (!pick) return false;
          resolved[i] = 1;
          chosen.push_back(*pick);
          return true;
        });
        times.lap(PhaseTimes::pick);
      }
      for (std::size_t k : chosen)
        if (!turn_of[slots[k]]) turn_of[slots[k]] = refined[k];
    }
  }
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

}  // namespace

ResolveResult resolve(Stand& s, DetectionBackend& backend, const ResolveRequest& req, const Contacts& initial) {
  const double t0 = now();
  PhaseTimes times;
  const ResolveConfig& cfg = req.config;
  if (cfg.level != ContactLevel::exact && cfg.level != ContactLevel::organ)
    throw std::invalid_argument("resolution detects at the exact or the organ level");
  if (initial.level != cfg.level)
    throw std::invalid_argument(fmt::format("resolution at the {} level was given contacts of the {} level", name_of(cfg.level),
                                            name_of(initial.level)));
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
    boxes[k] = make_obb(s.transforms[k], lib.get(r.prototype, r.lod).box, 0);
  };
#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::size_t k = 0; k < s.organ_count(); ++k) fit(k);
  Neighbourhood near(s, boxes, threads);
  ContactGraph touching;
  const TurnSearch search{s, joints, lib, cfg, dreq.collide, near, boxes, touching,
                          static_cast<float>(std::max<double>(cfg.clearance, dreq.clearance)), dreq.clearance};

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
  const AttemptRunner* told = nullptr;  // the runner that has seen every organ
  std::size_t best = left;
  int best_round = 0;
  std::vector<CandidatePool> pools(static_cast<std::size_t>(threads));
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
    if (req.progress) req.progress({round, left, now() - t0, left});
    ResolveRound rr;
    rr.round = round;
    rr.contacts = left;
    double t = now();
    times.lap(PhaseTimes::merge);  // the loop's own checks
    touching.build(s.organ_count(), contacts);
    // The runner of bulk attempts, if any (asked each round: it holds the stand as detected last),
    // told which organs moved since it last looked.
    AttemptRunner* runner = req.attempts ? req.attempts : req.bulk_attempts ? backend.attempt_runner(s) : nullptr;
    if (runner) runner->update_organs(s, boxes, changed, runner != told), told = runner;
    // The witnesses serve the host's attempts, and a bulk scan's runner tests them first.
    if (cfg.level == ContactLevel::exact) touching.find_witnesses(s, lib, search.clearance, threads);
    times.lap(PhaseTimes::witnesses);
    std::function<void(std::size_t)> planning;
    if (req.progress)
      planning = [&](std::size_t pending) { req.progress({round, left, now() - t0, pending}); };
    Plan plan = plan_round(s, joints, contacts, touching, search, threads, planning, part ? &part->plan : nullptr, runner, pools, times);
    why = std::move(plan.why);
    if (part)  // each process turns its own organs; the halo's turns come from their owners
      std::erase_if(plan.turns, [&](const Turn& turn) { return !mine(s.organs[turn.organ].plant); });
    rr.plan_s = now() - t;
    const auto planned = static_cast<std::size_t>(total({static_cast<std::int64_t>(plan.turns.size())})[0]);
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
    t = now();
    dreq.active_plants = &active;
    dreq.moved_organs = &moved_now;
    Contacts again = backend.redetect(s, dreq, moved);
    times.lap(PhaseTimes::redetect);
    dreq.active_plants = nullptr;
    dreq.moved_organs = nullptr;
    rr.detect_s = now() - t;
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
    rr.turned = planned;
    rr.plants_redetected = static_cast<std::size_t>(sums[1]);
    out.per_round.push_back(rr);
    out.rounds = round;
    why.clear();  // reasons belong to the list they were found on
  }
  times.lap(PhaseTimes::merge);
  // The candidates let go by the threads that made them, all at once.
#pragma omp parallel num_threads(threads)
  pools[static_cast<std::size_t>(omp_get_thread_num())].owned.clear();
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
    out.max_turn_deg = std::max(out.max_turn_deg, a);
  }
  for (std::size_t k = 0; k < s.organ_count(); ++k)
    if (mine(s.organs[k].plant)) ++owned_organs, carried_organs += carried[k];
  const std::vector<std::int64_t> sums = total({moved_joints, angle_units, owned_organs, carried_organs, owned_turned});
  if (part) out.max_turn_deg = part->max(out.max_turn_deg);
  out.organs_moved = static_cast<std::size_t>(sums[0]);
  if (out.organs_moved) out.mean_turn_deg = std::ldexp(static_cast<double>(sums[1]), -32) / static_cast<double>(out.organs_moved);
  out.organs_carried = static_cast<std::size_t>(sums[3]);
  out.joint_bytes = Joints::bytes_for(static_cast<std::size_t>(sums[2]), static_cast<std::size_t>(sums[4]));
  out.seconds = now() - t0;
  return out;
}

}  // namespace canopy
