// The attempts of a turn search: one turn tried against the pairs it must clear, the scan of a
// candidate's axes level by level, and the bisection of the turn found (the candidate's set-up,
// its pairs and neighbours, are in turn_search.cpp).
#include "resolution/turn_search.hpp"

#include <cmath>
#include <numbers>

namespace canopy {
namespace {

constexpr double kRad = std::numbers::pi / 180;

}  // namespace

bool TurnSearch::attempt(Candidate& c, const Vec3d& a, double deg, Mat3d& local, ExactScratch& scratch,
                         int axis) const {
  const Stand& s = stand;
  host_state(c);
  const Mat3d r = rotation(c, a, deg);
  // The joint's rotation is made only near its limit, or when the attempt succeeds.
  const bool limit_near = near_limit(c, deg);
  if (limit_near) {
    local = Joints::local_after(c.frame, r);
    if (rotation_angle_deg(local) > s.joint_limit_deg[c.mover] && !(deg <= c.chain_deg)) return false;
  }
  const Motion turn = rotation_about(c.joint, r);
  // Organ i of `moving` at this pose, made once per attempt when first needed.
  std::int32_t box_of = -1, pose_of = -1;
  Obb ox;
  Affine3f tx;
  const auto pose = [&](std::int32_t x) -> const Affine3f& {
    if (pose_of != x)
      tx = deg > 0 ? apply(turn, s.transforms[static_cast<std::size_t>(x)])
                   : s.transforms[static_cast<std::size_t>(x)],
      pose_of = x;
    return tx;
  };
  // Whether pair p of `set` (moving[i], keep[y[p]]) meets at this pose; `witness_tried`: its
  // witness triangles are known not to touch at this pose.
  const auto meets = [&](std::uint32_t set, std::size_t i, std::uint32_t p, bool witness_tried = false) {
    PairSet& pairs = set == 0 ? c.met_pairs : c.near_pairs;
    const std::uint32_t yi = pairs.y[p];
    const std::int32_t x = c.moving[i], y = c.keep[yi];
    if (box_of != x) ox = carried_box(boxes[static_cast<std::size_t>(x)], turn, clearance), box_of = x;
    const float gap = set == 0 ? clearance : detect_clearance;  // the organs met, or neighbours
    // The kept organ's box grown by the clearance it keeps, made here rather than kept per
    // candidate (a copy per neighbour of every candidate: 0.24 GB of the 10,000-plant CPU run's
    // 2.2 GB peak, heaptrack): the same bits either way, as the device's turned_boxes_meet.
    const Obb yb = grown(boxes[static_cast<std::size_t>(y)], gap);
    if (!obb_overlap(ox, yb, c.keep_off[yi])) return false;
    if (config.level == ContactLevel::organ) return true;
    const Affine3f& tx_now = pose(x);
    const Affine3f& ty = s.transforms[static_cast<std::size_t>(y)];
    // A neighbour pair without a witness gets one when its test finds a touch.
    Witness fresh;
    Witness* known = pairs.find(p);
    const bool touch =
        organs_touch_either(s, lib, x, tx_now, y, ty, gap, scratch, known ? known : &fresh, witness_tried);
    if (!known && fresh.latest >= 0) pairs.make(p) = fresh;
    return touch;
  };
  // Whether the triangles that touched last in pair p of `set` touch at this pose: a touch there
  // is a touch of the organs (their boxes overlap then too), found for the price of a few
  // triangle tests.
  const auto witness_meets = [&](std::uint32_t set, std::size_t i, std::uint32_t p, const Witness& w,
                                 int skip = -1) {
    if (w.latest < 0) return -1;
    const PairSet& pairs = set == 0 ? c.met_pairs : c.near_pairs;
    const std::int32_t x = c.moving[i], y = c.keep[pairs.y[p]];
    const Affine3f& tx_now = pose(x);
    const Affine3f& ty = s.transforms[static_cast<std::size_t>(y)];
    const float gap = set == 0 ? clearance : detect_clearance;
    return x < y ? witness_slot_touching(s, lib, x, tx_now, y, ty, gap, w, skip)
                 : witness_slot_touching(s, lib, y, ty, x, tx_now, gap, w, skip);
  };
  // What blocked this axis last, kept for the next attempt about it: the pair and, at the exact
  // level, the triangles that touched (the pair's newest witness slot).
  Candidate::AxisBlock* const memo = axis >= 0 && static_cast<std::size_t>(axis) < c.axis_block.size()
                                         ? &c.axis_block[static_cast<std::size_t>(axis)]
                                         : nullptr;
  const auto blocked_by = [&](std::uint32_t set, std::uint32_t i, std::uint32_t p) {
    if (!memo) return false;
    const Witness* w = (set == 0 ? c.met_pairs : c.near_pairs).find(p);
    memo->by = {set, i, p};
    const bool known = w && w->latest >= 0;
    memo->tri_a = known ? w->tri_a[w->latest] : Witness::kNone;
    memo->tri_b = known ? w->tri_b[w->latest] : Witness::kNone;
    return false;
  };
  // The pairs that blocked the last attempts first (nearby poses are blocked by the same pairs),
  // their witness triangles before any full test; the answer, a conjunction over the pairs, does
  // not depend on the order.
  const auto blocked_before = [&](std::uint32_t set, std::uint32_t p) {
    for (const Candidate::Blocker& b : c.blocker)
      if (b.pair == p && b.set == set) return true;
    return false;
  };
  const auto recent_blocker = [&](int n) -> const Candidate::Blocker& {  // n = 0: the latest
    return c.blocker[(c.latest_blocker - n + Candidate::kBlockers) % Candidate::kBlockers];
  };
  const bool exact = config.level != ContactLevel::organ;
  if (exact && memo && memo->by.pair != kNoPair && memo->tri_a != Witness::kNone) {
    Witness last;
    last.remember(memo->tri_a, memo->tri_b);
    if (witness_meets(memo->by.set, memo->by.organ, memo->by.pair, last) >= 0) return false;
  }
  for (int n = 0; exact && n < Candidate::kBlockers; ++n) {
    const Candidate::Blocker& b = recent_blocker(n);
    if (b.pair == kNoPair) continue;
    Witness* const w = (b.set == 0 ? c.met_pairs : c.near_pairs).find(b.pair);
    if (!w) continue;  // no triangles known to touch
    // The remembered triangles of this axis were just seen to miss.
    const int skip = memo && memo->by.pair == b.pair && memo->by.set == b.set && memo->tri_a != Witness::kNone
                         ? w->slot_of(memo->tri_a, memo->tri_b)
                         : -1;
    const int slot = witness_meets(b.set, b.organ, b.pair, *w, skip);
    if (slot >= 0) return w->promote(slot), blocked_by(b.set, b.organ, b.pair);
  }
  // A full test searches outwards from its pair's newest witness triangles: for the pair that
  // blocked this axis last, the triangles that touched about this axis, where the touch has
  // likely moved on to (1,000 plants: 70 k of 134 k attempts blocked by a recent blocker's full
  // test are blocked by that pair). Only the order of the work changes.
  if (exact && memo && memo->by.pair != kNoPair && memo->tri_a != Witness::kNone) {
    if (Witness* w = (memo->by.set == 0 ? c.met_pairs : c.near_pairs).find(memo->by.pair))
      w->promote(w->slot_of(memo->tri_a, memo->tri_b));
  }
  for (int n = 0; n < Candidate::kBlockers; ++n) {
    const Candidate::Blocker& b = recent_blocker(n);
    if (b.pair != kNoPair && meets(b.set, b.organ, b.pair, exact)) return blocked_by(b.set, b.organ, b.pair);
  }
  // Then the organs met (the likeliest to fail), then the neighbours to keep clear.
  for (std::uint32_t set = 0; set < 2; ++set) {
    if (set == 1) {
      if (!c.strict) break;
      if (c.near_deg < deg) gather_neighbours(c, deg), host_state(c);
    }
    const PairSet& pairs = set == 0 ? c.met_pairs : c.near_pairs;
    for (std::size_t i = 0; i < c.moving.size(); ++i)
      for (std::uint32_t p = pairs.first[i]; p < pairs.first[i + 1]; ++p) {
        if (blocked_before(set, p) || !meets(set, i, p)) continue;
        c.latest_blocker = (c.latest_blocker + 1) % Candidate::kBlockers;
        c.blocker[c.latest_blocker] = {set, static_cast<std::uint32_t>(i), p};
        return blocked_by(set, static_cast<std::uint32_t>(i), p);
      }
  }
  if (!limit_near) local = Joints::local_after(c.frame, r);
  return true;
}

Mat3d TurnSearch::rotation(Candidate& c, const Vec3d& a, double deg) const {
  if (deg != c.trig_deg)
    c.trig_deg = deg, c.trig_cos = std::cos(deg * kRad), c.trig_sin = std::sin(deg * kRad);
  return axis_angle(a, c.trig_cos, c.trig_sin);
}

bool TurnSearch::near_limit(const Candidate& c, double deg) const {
  // The joint's angle after the turn is at most deg + its angle now (rotation angles obey the
  // triangle inequality), so the limit needs checking only near it.
  return deg > 0 && deg + c.angle_now_deg > stand.joint_limit_deg[c.mover] - 1e-4;
}

bool TurnSearch::within_limit(Candidate& c, const Vec3d& a, double deg) const {
  return deg <= c.chain_deg || !near_limit(c, deg) ||
         rotation_angle_deg(local_after(c, a, deg)) <= stand.joint_limit_deg[c.mover];
}

Mat3d TurnSearch::local_after(Candidate& c, const Vec3d& a, double deg) const {
  return Joints::local_after(c.frame, rotation(c, a, deg));
}

bool TurnSearch::scan_level(Candidate& c, int level, ExactScratch& scratch) const {
  if (!c.searching()) return c.found_axis >= 0;
  const double step = std::max(config.scan_step_deg, config.angle_tolerance_deg);
  const double hi = std::min(level * step / c.weight, c.reach_deg);
  for (std::size_t i = 0; i < c.axes.size(); ++i) {
    Mat3d local;
    if (!attempt(c, c.axes[i], hi, local, scratch, static_cast<int>(i))) continue;
    c.found_axis = static_cast<int>(i);
    c.hi = hi;
    c.local = local;
    return true;
  }
  c.lo = hi;
  return false;
}

Turn TurnSearch::refine(Candidate& c, ExactScratch& scratch) const {
  // Bisect (lo, hi] on the axis found, down to the tolerance; b_hi stays feasible.
  const Vec3d& a = c.axes[static_cast<std::size_t>(c.found_axis)];
  double b_lo = c.lo, b_hi = c.hi;
  Mat3d best = c.local;
  while (b_hi - b_lo > config.angle_tolerance_deg) {
    const double mid = 0.5 * (b_lo + b_hi);
    Mat3d m;
    if (attempt(c, a, mid, m, scratch, c.found_axis)) b_hi = mid, best = m;
    else b_lo = mid;
  }
  return Turn{c.mover, best, b_hi};
}

}  // namespace canopy
