#include "resolution/resolve.hpp"

#include "resolution/background_release.hpp"
#include "resolution/resolve_steps.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>

namespace canopy {
namespace resolving {

ResolveResult Resolution::finish() {
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
  // The candidates and the lanes' tables go on a thread of their own (resolution/
  // background_release.hpp), and the lanes' threads end: every turn is made, the caller goes on.
  lane_threads.reset();
  if (req.statistics) {
    const auto bytes = [](const auto& t) { return t.capacity() * sizeof(t[0]); };
    for (std::size_t l = 0; l < tables.size() && l < lane_stats.size(); ++l) {
      PlanLaneStats& to = lane_stats[l];
      to.moving_bytes = bytes(tables[l].moving), to.keep_bytes = bytes(tables[l].keep),
      to.pair_bytes = bytes(tables[l].pairs);
      to.witness_bytes = bytes(tables[l].witness), to.axis_bytes = bytes(tables[l].axes);
    }
  }
  auto gone =
      std::make_shared<std::pair<std::vector<std::vector<CandidatePool>>, std::vector<AttemptTables>>>(
          std::move(pools), std::move(tables));
  BackgroundRelease::instance().hand_over([gone] { gone->first.clear(), gone->second.clear(); });
  times.lap(PhaseTimes::release);
  if (req.statistics) out.stats = statistics();
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
      out.max_turn_deg =
          std::max(out.max_turn_deg, rotation_angle_deg(joints.motion(static_cast<std::uint32_t>(k)).r));
  for (std::size_t k = 0; k < s.organ_count(); ++k)
    if (mine(s.organs[k].plant)) ++owned_organs, carried_organs += carried[k];
  const std::vector<std::int64_t> sums =
      total({moved_joints, angle_units, owned_organs, carried_organs, owned_turned});
  if (part) out.max_turn_deg = part->max(out.max_turn_deg), out.max_joint_deg = part->max(out.max_joint_deg);
  out.organs_moved = static_cast<std::size_t>(sums[0]);
  if (out.organs_moved)
    out.mean_turn_deg = std::ldexp(static_cast<double>(sums[1]), -32) / static_cast<double>(out.organs_moved);
  out.organs_carried = static_cast<std::size_t>(sums[3]);
  const std::vector<std::int64_t> bent = total(bend_counts);
  out.bends = static_cast<std::size_t>(bent[0]), out.bend_joints = static_cast<std::size_t>(bent[1]);
  out.kinks = static_cast<std::size_t>(bent[2]), out.unbent = static_cast<std::size_t>(bent[3]);
  out.joint_bytes = Joints::bytes_for(static_cast<std::size_t>(sums[2]), static_cast<std::size_t>(sums[4]));
  out.seconds = now_seconds() - t0;
  return std::move(out);
}

}  // namespace resolving

ResolveResult resolve(Stand& s, DetectionBackend& backend, const ResolveRequest& req,
                      const Contacts& initial) {
  resolving::Resolution r(s, backend, req, initial);
  for (int round = 1; !r.stopped(round); ++round) {
    resolving::Resolution::Round w = r.prepare_round(round);
    if (!r.plan_turns(w)) break;
    r.apply_round(w);
    r.detect_round(w);
    r.record_round(w);
  }
  return r.finish();
}

}  // namespace canopy
