// A turn search's candidates: what each mover carries and must clear, its axes, and the organ
// pairs a turn within its reach could bring together (the attempts themselves are in
// turn_attempt.cpp).
#include "resolution/turn_search.hpp"

#include "resolution/bend_chain.hpp"
#include "collision/contacts.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace canopy {
namespace {

constexpr double kRad = std::numbers::pi / 180;

Vec3d unit(Vec3f v) { return normalized(to_double(v)); }

/// The offset that carries organ k's plant frame into the frame of plant `into`.
Vec3f offset_into(const Stand& s, std::int32_t into, std::int32_t k) {
  const std::int32_t p = s.organs[static_cast<std::size_t>(k)].plant;
  return p == into ? Vec3f{0, 0, 0} : plant_offset(s, into, p);
}

}  // namespace

void TurnSearch::link_pairs(const Candidate& c, std::size_t from, std::size_t to, double max_deg,
                            PairSet& out) const {
  const Stand& s = stand;
  const std::int32_t plant = s.organs[c.mover].plant;
  out.clear();
  out.first.assign(1, 0);
  // Each organ kept clear, in the mover's plant frame: its centre, distance from the joint and
  // reach, as arrays of their own (lists kept per thread: a search links pairs hundreds of
  // thousands of times; the loops below read them through plain pointers, so that the
  // compiler keeps them in registers and the first loop over them has no branch).
  const std::size_t n = to - from;
  thread_local std::vector<double> lists;
  thread_local std::vector<std::uint8_t> passes;
  lists.resize(5 * n), passes.resize(n);
  double* const yx = lists.data();
  double* const yy = yx + n;
  double* const yz = yy + n;
  double* const dy = yz + n;
  double* const ry = dy + n;
  std::uint8_t* const pass = passes.data();
  for (std::size_t i = 0; i < n; ++i) {
    const std::int32_t y = c.keep[from + i];
    const Vec3f off = offset_into(s, plant, y);
    const Obb& oy = boxes[static_cast<std::size_t>(y)];
    const Vec3d cy = to_double(oy.centre + off);
    yx[i] = cy.x, yy[i] = cy.y, yz[i] = cy.z;
    dy[i] = length(cy - c.joint);
    ry[i] = oy.radius + 2.0 * clearance;
  }
  // A turn by at most max_deg moves a point at distance d from the joint by at most the chord
  // 2 d sin(max_deg / 2), and keeps it at distance d: pairs too far apart for either never meet.
  const double sin_half = std::sin(std::min(max_deg, 180.0) * kRad / 2);
  for (std::int32_t x : c.moving) {
    const Obb& ox = boxes[static_cast<std::size_t>(x)];
    const Vec3d cx = to_double(ox.centre);
    const double dx = length(cx - c.joint), chord = 2 * dx * sin_half, rx = ox.radius;
    for (std::size_t i = 0; i < n; ++i) {
      const double reach = rx + ry[i], slack = 1e-6 * (1 + dx + dy[i]);
      const double ex = yx[i] - cx.x, ey = yy[i] - cx.y, ez = yz[i] - cx.z;
      const double far = reach + chord + slack;
      // Not: the shells never meet, or too far for the largest turn.
      pass[i] = static_cast<std::uint8_t>(!(std::abs(dy[i] - dx) - reach > slack) &
                                          !(ex * ex + ey * ey + ez * ez > far * far));
    }
    const OrganRecord& rx_organ = s.organs[static_cast<std::size_t>(x)];
    for (std::size_t i = 0; i < n; ++i) {
      if (!pass[i]) continue;
      const std::int32_t y = c.keep[from + i];
      if (adjacent(rx_organ, x, s.organs[static_cast<std::size_t>(y)], y)) continue;
      out.y.push_back(static_cast<std::uint32_t>(from + i));
    }
    out.first.push_back(static_cast<std::uint32_t>(out.y.size()));
  }
}

void TurnSearch::Candidate::recycle() {
  Candidate old = std::move(*this);
  *this = Candidate{};
  const auto reuse = [](auto& to, auto& from) { from.clear(), to = std::move(from); };
  reuse(moving, old.moving), reuse(keep, old.keep), reuse(keep_off, old.keep_off);
  reuse(axes, old.axes), reuse(axis_block, old.axis_block);
  for (auto [to, from] : {std::pair{&met_pairs, &old.met_pairs}, std::pair{&near_pairs, &old.near_pairs}})
    reuse(to->first, from->first), reuse(to->y, from->y), reuse(to->witness, from->witness),
        reuse(to->slot, from->slot);
}

void TurnSearch::keep_offsets(Candidate& c, std::size_t from) const {
  const std::int32_t plant = stand.organs[c.mover].plant;
  c.keep_off.reserve(c.keep.size());
  std::int32_t last_plant = -1;
  Vec3f off;
  for (std::size_t i = from; i < c.keep.size(); ++i) {
    const std::int32_t y = c.keep[i];
    const std::int32_t p = stand.organs[static_cast<std::size_t>(y)].plant;
    if (p != last_plant)
      off = offset_into(stand, plant, y), last_plant = p;  // neighbours come plant by plant
    c.keep_off.push_back(off);
  }
}

void TurnSearch::host_state(Candidate& c) const {
  // The neighbours did not touch when the round began: no witness yet (met pairs have theirs
  // from prepare).
  TurnSearch::PairSet& near = c.near_pairs;
  near.sparse = true;
  if (near.slot.size() != near.y.size()) near.witness.clear(), near.slot.assign(near.y.size(), kNoPair);
}

TurnSearch::Candidate TurnSearch::prepare(std::uint32_t mover, const MetPairs& met_all, bool strict) const {
  Candidate c;
  prepare(c, mover, met_all, strict);
  return c;
}

void TurnSearch::prepare(Candidate& c, std::uint32_t mover, const MetPairs& met_all, bool strict) const {
  const Stand& s = stand;
  c.recycle();
  c.mover = mover;
  const std::int32_t plant = s.organs[mover].plant;
  const std::uint32_t end = joints.subtree_end(mover);
  c.joint = to_double(s.transforms[mover].t);
  c.frame = joints.joint_frame(mover);
  c.weight = config.kind_weight[static_cast<std::size_t>(s.organs[mover].kind)];
  c.angle_now_deg = joints.angle_deg(mover);
  c.chain_deg = unbendable && (*unbendable)[mover] ? 0.0 : chain_reach_deg(s, joints, config, mover);
  c.reach_deg = std::min(180.0, std::max<double>(s.joint_limit_deg[mover] + c.angle_now_deg, c.chain_deg));

  for (std::uint32_t k = mover; k < end; ++k)
    if (collide[static_cast<std::size_t>(s.organs[k].kind)]) c.moving.push_back(static_cast<std::int32_t>(k));
  // The pairs this mover separates: those with exactly one organ in its subtree.
  Vec3d away{0, 0, 0};
  for (auto [x, y] : met_all) {
    if (joints.holds(mover, y)) std::swap(x, y);
    if (!joints.holds(mover, x) || joints.holds(mover, y)) continue;
    c.keep.push_back(y);
    // The axis that swings x straight away from y.
    const Obb& ox = boxes[static_cast<std::size_t>(x)];
    const Obb& oy = boxes[static_cast<std::size_t>(y)];
    const Vec3d p = to_double(ox.centre), q = to_double(oy.centre + offset_into(s, plant, y));
    const Vec3d a = cross(p - c.joint, p - q);
    if (length(a) > 1e-12) away = away + normalized(a);
  }
  std::sort(c.keep.begin(), c.keep.end());
  c.keep.erase(std::unique(c.keep.begin(), c.keep.end()), c.keep.end());
  const std::size_t met = c.keep.size();
  c.met_count = met;

  c.strict = strict;
  keep_offsets(c, 0);
  link_pairs(c, 0, met, c.reach_deg, c.met_pairs);
  c.met_pairs.witness.assign(c.met_pairs.y.size(), Witness{});
  for (std::size_t i = 0; i < c.moving.size(); ++i)
    for (std::uint32_t p = c.met_pairs.first[i]; p < c.met_pairs.first[i + 1]; ++p)
      if (const Witness* w = touching.witness_of(c.moving[i], c.keep[c.met_pairs.y[p]]))
        c.met_pairs.witness[p] = *w;
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
  c.axis_block.assign(c.axes.size(), Candidate::AxisBlock{});
}

void TurnSearch::gather_neighbours(Candidate& c, double deg) const {
  const Stand& s = stand;
  const std::uint32_t mover = c.mover;
  const std::int32_t plant = s.organs[mover].plant;
  const std::size_t met = c.met_count;
  // Cover two scan levels beyond this turn, or twice what was covered before (a search that
  // keeps failing gathers O(log) times), never beyond the reach.
  const double level_deg = std::max(config.scan_step_deg, config.angle_tolerance_deg) / c.weight;
  const double cover = std::min(c.reach_deg, std::max(deg + 2 * level_deg, 2 * c.near_deg));
  c.near_deg = cover;
  c.keep.resize(met), c.keep_off.resize(met);
  for (Candidate::Blocker& b : c.blocker)
    if (b.set == 1) b = Candidate::Blocker{};
  for (Candidate::AxisBlock& b : c.axis_block)
    if (b.by.set == 1) b = Candidate::AxisBlock{};
  // The region the subtree can sweep: per moving organ the ball about its centre grown by its
  // chord, its radius and both clearances (link_pairs' test below, with room for its rounding
  // slack), and one box around them all; a neighbour's sphere must reach into that box.
  const double sin_half = std::sin(std::min(cover, 180.0) * kRad / 2);
  double reach = 0, lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (std::int32_t x : c.moving) {
    const Obb& ox = boxes[static_cast<std::size_t>(x)];
    const Vec3d cx = to_double(ox.centre);
    const double dx = length(cx - c.joint);
    reach = std::max(reach, dx + ox.radius);
    const double swept = ox.radius + 2 * dx * sin_half + 2.0 * clearance;
    const double r = swept + 1e-4 + 2e-6 * (1 + dx + swept);
    const double p[3] = {cx.x, cx.y, cx.z};
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], p[a] - r), hi[a] = std::max(hi[a], p[a] + r);
  }
  reach += clearance;
  // Whether a box (corners a, b) misses the swept box.
  const auto box_misses = [&](const Vec3d& a, const Vec3d& b) {
    return b.x < lo[0] || a.x > hi[0] || b.y < lo[1] || a.y > hi[1] || b.z < lo[2] || a.z > hi[2];
  };
  // Organs already touching the subtree are other contacts' business.
  thread_local std::vector<std::int32_t> busy;
  busy.clear();
  for (std::int32_t x : c.moving)
    for (std::uint32_t e = touching.first[static_cast<std::size_t>(x)];
         e < touching.first[static_cast<std::size_t>(x) + 1]; ++e)
      busy.push_back(touching.with[e]);
  std::sort(busy.begin(), busy.end());
  const Vec3d origin = s.offset(static_cast<std::size_t>(plant));
  const double joint_norm = length(c.joint);
  // Plants near the swept box's horizontal centre (or the joint's reach, if smaller).
  double qx = 0.5 * (lo[0] + hi[0]), qy = 0.5 * (lo[1] + hi[1]);
  double qr = 0.5 * std::hypot(hi[0] - lo[0], hi[1] - lo[1]);
  if (qr > reach) qx = c.joint.x, qy = c.joint.y, qr = reach;
  for (std::int32_t q : near.plants_near(s, origin.x + qx, origin.y + qy, qr)) {
    const PlantRecord& pr = s.plants[static_cast<std::size_t>(q)];
    const Vec3f off = offset_into(s, plant, static_cast<std::int32_t>(pr.first_organ));
    for (const OrganRun& run : near.runs(q)) {
      // A run whose sphere lies beyond the reach, or whose box (carried by the offset) misses the
      // swept box, holds no organ that passes the tests below (the slack covers the float sums
      // of centre and offset).
      const Vec3d rc = to_double(run.centre) + to_double(off);
      const double gap = length(rc - c.joint);
      if (gap - 1e-6 * (1 + gap + joint_norm + run.radius) > reach + run.radius + clearance) continue;
      const double slack = 1e-5 * (1 + gap + joint_norm);
      if (box_misses(to_double(run.lo) + to_double(off) - Vec3d{slack, slack, slack},
                     to_double(run.hi) + to_double(off) + Vec3d{slack, slack, slack}))
        continue;
      for (std::uint32_t k = run.first; k < run.end; ++k) {
        const auto y = static_cast<std::int32_t>(k);
        const Obb& raw = boxes[k];
        const Vec3d cy = to_double(raw.centre + off);
        const double r = raw.radius;
        // The swept box first: it turns most organs of a run away (whether the organ's sphere
        // misses it, every comparison made and one branch taken: which pass is hard to predict).
        const bool out = (cy.x + r < lo[0]) | (cy.x - r > hi[0]) | (cy.y + r < lo[1]) | (cy.y - r > hi[1]) |
                         (cy.z + r < lo[2]) | (cy.z - r > hi[2]);
        if (out || joints.holds(mover, y) || !collide[static_cast<std::size_t>(s.organs[k].kind)]) continue;
        if (length(cy - c.joint) > reach + raw.radius + clearance) continue;
        if (std::binary_search(c.keep.begin(), c.keep.begin() + static_cast<std::ptrdiff_t>(met), y))
          continue;
        if (std::binary_search(busy.begin(), busy.end(), y)) continue;
        c.keep.push_back(y);
      }
    }
  }
  link_pairs(c, met, c.keep.size(), cover, c.near_pairs);
  // Only the neighbours some pair names stay (in their order; the pairs renumbered).
  thread_local std::vector<std::uint32_t> renumber;
  renumber.assign(c.keep.size(), kNoPair);
  for (std::uint32_t k : c.near_pairs.y) renumber[k] = 0;
  std::size_t kept = met;
  for (std::size_t k = met; k < c.keep.size(); ++k)
    if (renumber[k] == 0) renumber[k] = static_cast<std::uint32_t>(kept), c.keep[kept++] = c.keep[k];
  c.keep.resize(kept);
  for (std::uint32_t& k : c.near_pairs.y) k = renumber[k];
  keep_offsets(c, met);
}

}  // namespace canopy
