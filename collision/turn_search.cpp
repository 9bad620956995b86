#include "collision/turn_search.hpp"

#include "collision/contacts.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace canopy {
namespace {

constexpr double kRad = std::numbers::pi / 180;

Vec3d unit(Vec3f v) { return normalized(to_double(v)); }

/// The OBB `o` carried by the rigid motion `m` and grown by `inflate`; the rounding slack of the
/// original box covers the float rounding of the carried one.
Obb carried_box(const Obb& o, const Motion& m, float inflate) {
  Obb r;
  r.centre = to_float(apply(m, to_double(o.centre)));
  for (int k = 0; k < 3; ++k) r.axis[k] = to_float(m.r * to_double(o.axis[k])), r.half[k] = o.half[k] + inflate;
  set_radius(r);
  return r;
}

}  // namespace

void ContactGraph::build(std::size_t organs, const std::vector<Contact>& contacts) {
  first.assign(organs + 1, 0);
  for (const Contact& c : contacts) ++first[static_cast<std::size_t>(c.organ_a) + 1], ++first[static_cast<std::size_t>(c.organ_b) + 1];
  for (std::size_t i = 0; i < organs; ++i) first[i + 1] += first[i];
  with.resize(first[organs]);
  std::vector<std::uint32_t> at(first.begin(), first.end() - 1);
  for (const Contact& c : contacts) {
    with[at[static_cast<std::size_t>(c.organ_a)]++] = c.organ_b;
    with[at[static_cast<std::size_t>(c.organ_b)]++] = c.organ_a;
  }
}

void TurnSearch::Candidate::link_pairs(const Stand& s, const std::vector<Obb>& boxes, float clearance) {
  const std::int32_t plant = s.organs[mover].plant;
  pair_first.assign(1, 0);
  pair_y.clear();
  // Each organ kept clear, in the mover's plant frame: its centre and reach.
  std::vector<Vec3d> cy(keep.size());
  std::vector<double> dy(keep.size()), ry(keep.size());
  for (std::size_t i = 0; i < keep.size(); ++i) {
    const std::int32_t y = keep[i];
    const std::int32_t py = s.organs[static_cast<std::size_t>(y)].plant;
    const Vec3f off = py == plant ? Vec3f{0, 0, 0} : plant_offset(s, plant, py);
    const Obb& oy = boxes[static_cast<std::size_t>(y)];
    cy[i] = to_double(oy.centre + off);
    dy[i] = length(cy[i] - joint);
    ry[i] = oy.radius + 2.0 * clearance;
  }
  // A turn by at most reach_deg moves a point at distance d from the joint by at most the chord
  // 2 d sin(reach / 2), and keeps it at distance d: pairs too far apart for either never meet.
  const double half = std::min(reach_deg, 180.0) * kRad / 2;
  for (std::int32_t x : moving) {
    const Obb& ox = boxes[static_cast<std::size_t>(x)];
    const Vec3d cx = to_double(ox.centre);
    const double dx = length(cx - joint), chord = 2 * dx * std::sin(half);
    for (std::size_t i = 0; i < keep.size(); ++i) {
      const double reach = ox.radius + ry[i], slack = 1e-6 * (1 + dx + dy[i]);
      if (std::abs(dy[i] - dx) - reach > slack) continue;               // the shells never meet
      const double far = reach + chord + slack;
      if (dot(cy[i] - cx, cy[i] - cx) > far * far) continue;            // too far for the largest turn
      const std::int32_t y = keep[i];
      if (adjacent(s.organs[static_cast<std::size_t>(x)], x, s.organs[static_cast<std::size_t>(y)], y)) continue;
      pair_y.push_back(static_cast<std::uint32_t>(i));
    }
    pair_first.push_back(static_cast<std::uint32_t>(pair_y.size()));
  }
  witness.assign(pair_y.size(), Witness{});
}

TurnSearch::Candidate TurnSearch::prepare(std::uint32_t mover, const MetPairs& met_all, bool strict) const {
  const Stand& s = stand;
  Candidate c;
  c.mover = mover;
  const std::int32_t plant = s.organs[mover].plant;
  const std::uint32_t end = joints.subtree_end(mover);
  c.joint = to_double(s.transforms[mover].t);
  c.frame = joints.joint_frame(mover);
  c.weight = config.kind_weight[static_cast<std::size_t>(s.organs[mover].kind)];
  c.reach_deg = std::min(180.0, s.joint_limit_deg[mover] + joints.angle_deg(mover));
  const auto offset_to = [&](std::int32_t k) {  // carries organ k's plant frame into the mover's
    const std::int32_t p = s.organs[static_cast<std::size_t>(k)].plant;
    return p == plant ? Vec3f{0, 0, 0} : plant_offset(s, plant, p);
  };
  const auto in_subtree = [&](std::int32_t k) { return static_cast<std::uint32_t>(k) >= mover && static_cast<std::uint32_t>(k) < end; };

  for (std::uint32_t k = mover; k < end; ++k)
    if (collide[static_cast<std::size_t>(s.organs[k].kind)]) c.moving.push_back(static_cast<std::int32_t>(k));
  // The pairs this mover separates: those with exactly one organ in its subtree.
  Vec3d away{0, 0, 0};
  for (auto [x, y] : met_all) {
    if (in_subtree(y)) std::swap(x, y);
    if (!in_subtree(x) || in_subtree(y)) continue;
    c.keep.push_back(y);
    // The axis that swings x straight away from y.
    const Obb& ox = boxes[static_cast<std::size_t>(x)];
    const Obb& oy = boxes[static_cast<std::size_t>(y)];
    const Vec3d p = to_double(ox.centre), q = to_double(oy.centre + offset_to(y));
    const Vec3d a = cross(p - c.joint, p - q);
    if (length(a) > 1e-12) away = away + normalized(a);
  }
  std::sort(c.keep.begin(), c.keep.end());
  c.keep.erase(std::unique(c.keep.begin(), c.keep.end()), c.keep.end());
  const std::size_t met = c.keep.size();
  c.met_count = met;

  // Strict: also every organ within the subtree's reach about the joint that is clear now.
  if (strict) {
    double reach = 0;
    for (std::int32_t x : c.moving) {
      const Obb& ox = boxes[static_cast<std::size_t>(x)];
      reach = std::max(reach, length(to_double(ox.centre) - c.joint) + ox.radius);
    }
    reach += clearance;
    // Organs already touching the subtree are other contacts' business.
    std::vector<std::int32_t> busy;
    for (std::int32_t x : c.moving)
      for (std::uint32_t e = touching.first[static_cast<std::size_t>(x)]; e < touching.first[static_cast<std::size_t>(x) + 1]; ++e)
        busy.push_back(touching.with[e]);
    std::sort(busy.begin(), busy.end());
    const Vec3d origin = s.offset(static_cast<std::size_t>(plant));
    const double joint_norm = length(c.joint);
    for (std::int32_t q : near.plants_near(s, origin.x + c.joint.x, origin.y + c.joint.y, reach)) {
      const PlantRecord& pr = s.plants[static_cast<std::size_t>(q)];
      const Vec3f off = offset_to(static_cast<std::int32_t>(pr.first_organ));
      for (const OrganRun& run : near.runs(q)) {
        // A run whose sphere lies beyond the reach holds no organ that passes the test below
        // (the slack covers the float sums of centre and offset).
        const double gap = length(to_double(run.centre) + to_double(off) - c.joint);
        if (gap - 1e-6 * (1 + gap + joint_norm + run.radius) > reach + run.radius + clearance) continue;
      for (std::uint32_t k = run.first; k < run.end; ++k) {
        const auto y = static_cast<std::int32_t>(k);
        if (in_subtree(y) || !collide[static_cast<std::size_t>(s.organs[k].kind)]) continue;
        const Obb& raw = boxes[k];
        if (length(to_double(raw.centre + off) - c.joint) > reach + raw.radius + clearance) continue;
        if (std::binary_search(c.keep.begin(), c.keep.begin() + static_cast<std::ptrdiff_t>(met), y)) continue;
        if (std::binary_search(busy.begin(), busy.end(), y)) continue;
        c.keep.push_back(y);
      }
      }
    }
  }

  c.link_pairs(s, boxes, clearance);
  const Affine3f& tm = s.transforms[mover];
  if (length(away) > 1e-9) c.axes.push_back(normalized(away));
  const Vec3d h = unit(tm.c0), l = unit(tm.c1), u = unit(tm.c2);
  const int fan = std::max(4, config.axis_fan);
  for (int i = 0; i < fan; ++i) {
    const double phi = 2 * std::numbers::pi * i / fan;
    const Vec3d a = l * std::cos(phi) + u * std::sin(phi);
    if (length(a) > 0.5) c.axes.push_back(normalized(a));
  }
  for (Vec3d a : {h, h * -1.0})
    if (length(a) > 0.5) c.axes.push_back(a);
  return c;
}

bool TurnSearch::attempt(const Candidate& c, const Vec3d& a, double deg, Mat3d& local, ExactScratch& scratch) const {
  const Stand& s = stand;
  const Mat3d r = axis_angle(a, deg * kRad);
  local = Joints::local_after(c.frame, r);
  if (deg > 0 && rotation_angle_deg(local) > s.joint_limit_deg[c.mover]) return false;
  const Motion turn = rotation_about(c.joint, r);
  const std::int32_t plant = s.organs[c.mover].plant;
  // Organ i of `moving` at this pose, made once per attempt when first needed.
  std::int32_t box_of = -1, pose_of = -1;
  Obb ox;
  Affine3f tx;
  // Whether pair p (moving[i], keep[pair_y[p]]) meets at this pose.
  const auto meets = [&](std::size_t i, std::uint32_t p) {
    const std::uint32_t yi = c.pair_y[p];
    const std::int32_t x = c.moving[i], y = c.keep[yi];
    const std::int32_t py = s.organs[static_cast<std::size_t>(y)].plant;
    const Vec3f off = py == plant ? Vec3f{0, 0, 0} : plant_offset(s, plant, py);
    if (box_of != x) ox = carried_box(boxes[static_cast<std::size_t>(x)], turn, clearance), box_of = x;
    const bool met = yi < c.met_count;
    if (!obb_overlap(ox, grown(boxes[static_cast<std::size_t>(y)], met ? clearance : detect_clearance), off)) return false;
    if (config.level == ContactLevel::organ) return true;
    if (pose_of != x) tx = deg > 0 ? apply(turn, s.transforms[static_cast<std::size_t>(x)]) : s.transforms[static_cast<std::size_t>(x)], pose_of = x;
    const Affine3f& ty = s.transforms[static_cast<std::size_t>(y)];
    const float gap = met ? clearance : detect_clearance;
    Witness* w = &c.witness[p];
    return x < y ? organs_touch_at(s, lib, x, tx, y, ty, gap, scratch, w) : organs_touch_at(s, lib, y, ty, x, tx, gap, scratch, w);
  };
  // The pair that blocked the last attempt first (nearby poses are blocked by the same pair);
  // the answer, a conjunction over the pairs, does not depend on the order.
  const auto blocked_before = [&](std::uint32_t p) {
    for (const Candidate::Blocker& b : c.blocker)
      if (b.pair == p) return true;
    return false;
  };
  for (int n = 0; n < Candidate::kBlockers; ++n) {
    const Candidate::Blocker& b = c.blocker[(c.latest_blocker - n + Candidate::kBlockers) % Candidate::kBlockers];
    if (b.pair != kNoPair && meets(b.organ, b.pair)) return false;
  }
  // Then the organs met first (the likeliest to fail), then the neighbours to keep clear.
  for (int pass = 0; pass < 2; ++pass)
    for (std::size_t i = 0; i < c.moving.size(); ++i)
      for (std::uint32_t p = c.pair_first[i]; p < c.pair_first[i + 1]; ++p) {
        if ((c.pair_y[p] < c.met_count) != (pass == 0) || blocked_before(p)) continue;
        if (meets(i, p)) {
          c.latest_blocker = (c.latest_blocker + 1) % Candidate::kBlockers;
          c.blocker[c.latest_blocker] = {static_cast<std::uint32_t>(i), p};
          return false;
        }
      }
  return true;
}

bool TurnSearch::scan_level(Candidate& c, int level, ExactScratch& scratch) const {
  if (c.found_axis >= 0 || c.exhausted()) return c.found_axis >= 0;
  const double step = std::max(config.scan_step_deg, config.angle_tolerance_deg);
  const double hi = std::min(level * step / c.weight, c.reach_deg);
  for (std::size_t i = 0; i < c.axes.size(); ++i) {
    Mat3d local;
    if (!attempt(c, c.axes[i], hi, local, scratch)) continue;
    c.found_axis = static_cast<int>(i);
    c.hi = hi;
    c.local = local;
    return true;
  }
  c.lo = hi;
  return false;
}

Turn TurnSearch::refine(const Candidate& c, ExactScratch& scratch) const {
  // Bisect (lo, hi] on the axis found, down to the tolerance; b_hi stays feasible.
  const Vec3d& a = c.axes[static_cast<std::size_t>(c.found_axis)];
  double b_lo = c.lo, b_hi = c.hi;
  Mat3d best = c.local;
  while (b_hi - b_lo > config.angle_tolerance_deg) {
    const double mid = 0.5 * (b_lo + b_hi);
    Mat3d m;
    if (attempt(c, a, mid, m, scratch)) b_hi = mid, best = m;
    else b_lo = mid;
  }
  return Turn{c.mover, best, b_hi};
}

}  // namespace canopy
