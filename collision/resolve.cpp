#include "collision/resolve.hpp"

#include "collision/turn_search.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <stdexcept>

namespace canopy {
namespace {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

struct Plan {
  std::vector<Turn> turns;                   // by organ id
  std::map<std::size_t, std::string> why;    // contacts no turn took care of, by index
};

/// One round's turns, all planned against the poses at the start of the round. Each contact goes
/// to its first candidate mover; a mover's contacts are separated together by one turn; where a
/// mover cannot separate its contacts within its joint limit, they go on to their next candidate.
Plan plan_round(const Stand& s, const Joints& joints, const std::vector<Contact>& contacts, const TurnSearch& search,
                int threads) {
  const ResolveConfig& cfg = search.config;
  const std::size_t n = contacts.size();
  std::vector<std::vector<std::uint32_t>> cands(n);
  std::vector<std::string> no_mover(n);
  for (std::size_t i = 0; i < n; ++i) cands[i] = candidate_movers(s, joints, contacts[i], cfg, no_mover[i]);
  std::vector<std::size_t> next(n, 0);
  std::vector<std::uint8_t> done(n, 0);
  std::map<std::uint32_t, Turn> locked;                 // movers with a turn
  std::map<std::uint32_t, std::uint8_t> failed;         // movers that could not separate their contacts
  Plan plan;
  for (;;) {
    // Each pending contact's current candidate: skip movers already decided.
    std::map<std::uint32_t, std::vector<std::size_t>> groups;
    for (std::size_t i = 0; i < n; ++i) {
      if (done[i]) continue;
      while (next[i] < cands[i].size() && (locked.count(cands[i][next[i]]) || failed.count(cands[i][next[i]]))) ++next[i];
      if (next[i] == cands[i].size()) {
        done[i] = 1;
        plan.why[i] = cands[i].empty() ? no_mover[i]
                                        : fmt::format("no turn within the joint limits of the {} organ(s) that may carry them "
                                                      "separates them",
                                                      cands[i].size());
        continue;
      }
      groups[cands[i][next[i]]].push_back(i);
    }
    if (groups.empty()) break;
    std::vector<std::pair<std::uint32_t, std::vector<std::size_t>>> work(groups.begin(), groups.end());
    std::vector<std::optional<Turn>> found(work.size());
#pragma omp parallel num_threads(threads)
    {
      ExactScratch scratch;
      std::vector<std::pair<std::int32_t, std::int32_t>> met;
#pragma omp for schedule(dynamic, 1)
      for (std::size_t g = 0; g < work.size(); ++g) {
        const std::uint32_t mover = work[g].first;
        const std::uint32_t end = joints.subtree_end(mover);
        met.clear();
        for (std::size_t i : work[g].second) {
          const Contact& c = contacts[i];
          const bool a_moves = static_cast<std::uint32_t>(c.organ_a) >= mover && static_cast<std::uint32_t>(c.organ_a) < end;
          met.emplace_back(a_moves ? c.organ_a : c.organ_b, a_moves ? c.organ_b : c.organ_a);
        }
        found[g] = search.find(mover, met, scratch);
      }
    }
    for (std::size_t g = 0; g < work.size(); ++g) {
      if (found[g]) {
        locked.emplace(work[g].first, *found[g]);
        for (std::size_t i : work[g].second) done[i] = 1;
      } else {
        failed.emplace(work[g].first, 1);
      }
    }
  }
  for (const auto& [organ, turn] : locked) plan.turns.push_back(turn);
  return plan;
}

}  // namespace

ResolveResult resolve(Stand& s, DetectionBackend& backend, const ResolveRequest& req, const Contacts& initial) {
  const double t0 = now();
  const ResolveConfig& cfg = req.config;
  if (cfg.level != ContactLevel::exact && cfg.level != ContactLevel::organ)
    throw std::invalid_argument("resolution detects at the exact or the organ level");
  if (initial.level != cfg.level)
    throw std::invalid_argument(fmt::format("resolution at the {} level was given contacts of the {} level", name_of(cfg.level),
                                            name_of(initial.level)));
  ResolveResult out;
  Joints joints(s);
  PrototypeLibrary lib;
  for (const OrganRecord& r : s.organs) lib.get(r.prototype, r.lod);  // made before threads share them
  DetectRequest dreq = req.detect;
  dreq.level = cfg.level;
  const int threads = dreq.threads > 0 ? dreq.threads : omp_get_max_threads();
  const TurnSearch search{s, joints, lib, cfg, dreq.collide, static_cast<float>(std::max<double>(cfg.clearance, dreq.clearance))};

  std::vector<Contact> contacts = initial.pairs;
  out.contacts_before = contacts.size();
  std::vector<std::uint8_t> carried(s.organ_count(), 0);
  std::map<std::size_t, std::string> why;
  for (int round = 1;; ++round) {
    if (contacts.empty()) {
      out.converged = true;
      out.stop = "no contact left";
      break;
    }
    if (round > cfg.max_rounds) {
      out.stop = fmt::format("round cap ({}) reached", cfg.max_rounds);
      break;
    }
    if (req.progress) req.progress({round, contacts.size(), now() - t0});
    ResolveRound rr;
    rr.round = round;
    rr.contacts = contacts.size();
    double t = now();
    Plan plan = plan_round(s, joints, contacts, search, threads);
    why = std::move(plan.why);
    rr.plan_s = now() - t;
    if (plan.turns.empty()) {
      out.stop = "no turn within the joint limits separates the contacts left";
      out.per_round.push_back(rr);
      break;
    }
    std::vector<std::uint32_t> turned;
    for (const Turn& turn : plan.turns) {
      joints.set_local(turn.organ, turn.local);
      turned.push_back(turn.organ);
    }
    const std::vector<std::uint32_t> moved = joints.update(s, turned);
    std::vector<std::uint8_t> active(s.plant_count(), 0);
    for (std::uint32_t k : moved) {
      const Affine3f& m = s.transforms[k];
      for (float v : {m.c0.x, m.c0.y, m.c0.z, m.c1.x, m.c1.y, m.c1.z, m.c2.x, m.c2.y, m.c2.z, m.t.x, m.t.y, m.t.z})
        if (!std::isfinite(v)) throw std::logic_error(fmt::format("resolution made a non-finite transform for organ {}", k));
      carried[k] = 1;
      active[static_cast<std::size_t>(s.organs[k].plant)] = 1;
    }
    t = now();
    dreq.active_plants = &active;
    Contacts again = backend.redetect(s, dreq, moved);
    dreq.active_plants = nullptr;
    rr.detect_s = now() - t;
    std::erase_if(contacts, [&](const Contact& c) {
      return active[static_cast<std::size_t>(c.plant_a)] || active[static_cast<std::size_t>(c.plant_b)];
    });
    contacts.insert(contacts.end(), again.pairs.begin(), again.pairs.end());
    std::sort(contacts.begin(), contacts.end());
    rr.turned = turned.size();
    rr.plants_redetected = static_cast<std::size_t>(std::count(active.begin(), active.end(), 1));
    out.per_round.push_back(rr);
    out.rounds = round;
    why.clear();  // reasons belong to the list they were found on
  }
  out.contacts_after = contacts.size();
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const auto w = why.find(i);
    out.unresolved.push_back(
        {contacts[i], w != why.end() ? w->second : "still in contact when the round cap was reached"});
  }
  for (std::uint32_t k : joints.turned()) {
    const double a = joints.angle_deg(k);
    if (a <= 0) continue;
    ++out.organs_moved;
    out.mean_turn_deg += a;
    out.max_turn_deg = std::max(out.max_turn_deg, a);
  }
  if (out.organs_moved) out.mean_turn_deg /= static_cast<double>(out.organs_moved);
  out.organs_carried = static_cast<std::size_t>(std::count(carried.begin(), carried.end(), 1));
  out.joint_bytes = joints.bytes();
  out.seconds = now() - t0;
  return out;
}

}  // namespace canopy
