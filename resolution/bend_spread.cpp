#include "resolution/bend_spread.hpp"

#include "collision/contacts.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

namespace canopy {
namespace {

constexpr double kDeg = 180 / std::numbers::pi;

/// The rotation of a turn in the plant frame, its axis and angle: Joints::local_after makes the
/// joint's rotation Q_after = P^T R P Q_before (P its parent's rotation), so
/// R = P Q_after Q_before^T P^T.
struct Rotation {
  Vec3d axis;
  double deg = 0;
};

std::optional<Rotation> turn_rotation(const Joints& joints, const Turn& t) {
  const Joints::JointFrame f = joints.joint_frame(t.organ);
  const Mat3d r = f.parent * t.local * transpose(f.local) * f.parent_t;
  // The axis from the skew part (the angle lies well inside (0, 180): joint limits are below it).
  const Vec3d v{r.m[7] - r.m[5], r.m[2] - r.m[6], r.m[3] - r.m[1]};
  const double n = length(v);
  if (!(n > 1e-12)) return std::nullopt;
  return Rotation{v * (1 / n), rotation_angle_deg(r)};
}

/// Whether organ x is the other's neighbour by construction (never a contact) or not collided.
bool skip_pair(const Stand& s, const KindMask& collide, std::int32_t x, std::int32_t y) {
  const OrganRecord &rx = s.organs[static_cast<std::size_t>(x)], &ry = s.organs[static_cast<std::size_t>(y)];
  return !collide[static_cast<std::size_t>(ry.kind)] || adjacent(rx, x, ry, y);
}

bool touched(const ContactGraph& g, std::int32_t x, std::int32_t y) {
  for (std::uint32_t e = g.first[static_cast<std::size_t>(x)]; e < g.first[static_cast<std::size_t>(x) + 1];
       ++e)
    if (g.with[e] == y) return true;
  return false;
}

Mat3d turn_by(const Vec3d& axis, double deg) {
  return axis_angle(axis, std::cos(deg / kDeg), std::sin(deg / kDeg));
}

/// Whether the chain c (proximal first) turned by deg[i] about `axis` at joint c[i] leaves every
/// pair it moves as the header says: the organs of k's subtree clear of all, the others meeting
/// only what they met before.
bool bend_passes(const TurnSearch& ts, const std::vector<std::uint32_t>& c, const Vec3d& axis,
                 const std::vector<double>& deg, ExactScratch& scratch) {
  const Stand& s = ts.stand;
  const std::uint32_t first = c.front(), end = ts.joints.subtree_end(first), k = c.back();
  // The motion of each level: the turns of the joints above it, distal first.
  std::vector<Motion> level(c.size());
  Motion m;
  for (std::size_t i = 0; i < c.size(); ++i) {
    m = compose(m, rotation_about(to_double(s.transforms[c[i]].t), turn_by(axis, deg[i])));
    level[i] = m;
  }
  const std::int32_t plant = s.organs[first].plant;
  struct Moved {
    std::int32_t organ;
    std::size_t level;
    Affine3f pose;
    Obb box;
  };
  std::vector<Moved> moved;
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  const float gap = std::max(ts.clearance, ts.detect_clearance);
  for (std::uint32_t x = first; x < end; ++x) {
    if (!ts.collide[static_cast<std::size_t>(s.organs[x].kind)]) continue;
    std::size_t l = 0;
    while (l + 1 < c.size() && ts.joints.holds(c[l + 1], static_cast<std::int32_t>(x))) ++l;
    const Obb b = carried_box(ts.boxes[x], level[l], 0);
    moved.push_back({static_cast<std::int32_t>(x), l, apply(level[l], s.transforms[x]), b});
    const double ctr[3] = {b.centre.x, b.centre.y, b.centre.z};
    for (int a = 0; a < 3; ++a)
      lo[a] = std::min(lo[a], ctr[a] - b.radius), hi[a] = std::max(hi[a], ctr[a] + b.radius);
  }
  // Whether x at its new pose and y (at `ty`, moved by `off`) meet, and whether that is allowed.
  const auto fails = [&](const Moved& x, std::int32_t y, const Affine3f& ty, const Obb& by, Vec3f off) {
    const bool in_k = ts.joints.holds(k, x.organ) || ts.joints.holds(k, y);
    const bool before = touched(ts.touching, x.organ, y);
    const float need = before ? ts.clearance : ts.detect_clearance;
    if (before && !in_k)
      return false;  // a contact of the chain's own that the kink would not have moved either
    if (!obb_overlap(grown(x.box, gap), by, off)) return false;
    if (ts.config.level == ContactLevel::organ) return true;
    return organs_touch_either(s, ts.lib, x.organ, x.pose, y, ty, need, scratch);
  };
  // Pairs within the moving subtree whose motions differ.
  for (std::size_t i = 0; i < moved.size(); ++i)
    for (std::size_t j = i + 1; j < moved.size(); ++j) {
      if (moved[i].level == moved[j].level || skip_pair(s, ts.collide, moved[i].organ, moved[j].organ))
        continue;
      if (fails(moved[i], moved[j].organ, moved[j].pose, moved[j].box, Vec3f{0, 0, 0})) return false;
    }
  // Everything else within reach: plants near the moved organs' box, their runs, their organs.
  const double pad = 2.0 * gap + 1e-4;
  const Vec3d origin = s.offset(static_cast<std::size_t>(plant));
  const double cx = 0.5 * (lo[0] + hi[0]), cy = 0.5 * (lo[1] + hi[1]);
  const double cr = 0.5 * std::hypot(hi[0] - lo[0], hi[1] - lo[1]) + pad;
  for (std::int32_t q : ts.near.plants_near(s, origin.x + cx, origin.y + cy, cr)) {
    const Vec3f off = q == plant ? Vec3f{0, 0, 0} : plant_offset(s, plant, q);
    for (const OrganRun& run : ts.near.runs(q)) {
      const double slack = 1e-5 * (1 + std::fabs(cx) + std::fabs(cy) + run.radius);
      const Vec3d rlo = to_double(run.lo) + to_double(off), rhi = to_double(run.hi) + to_double(off);
      if (rhi.x + pad + slack < lo[0] || rlo.x - pad - slack > hi[0] || rhi.y + pad + slack < lo[1] ||
          rlo.y - pad - slack > hi[1] || rhi.z + pad + slack < lo[2] || rlo.z - pad - slack > hi[2])
        continue;
      for (std::uint32_t y = run.first; y < run.end; ++y) {
        if (y >= first && y < end && q == plant) continue;  // moving: tested above
        const auto yi = static_cast<std::int32_t>(y);
        for (const Moved& x : moved) {
          if (skip_pair(s, ts.collide, x.organ, yi)) continue;
          if (fails(x, yi, s.transforms[y], ts.boxes[y], off)) return false;
        }
      }
    }
  }
  return true;
}

}  // namespace

std::vector<Turn> spread_turns(const TurnSearch& ts, const std::vector<Turn>& turns, int threads,
                               SpreadStats* stats) {
  const Stand& s = ts.stand;
  const ResolveConfig& cfg = ts.config;
  if (cfg.bend_joints <= 1) return turns;
  std::vector<std::uint8_t> planned(s.organ_count(), 0);
  for (const Turn& t : turns) planned[t.organ] = 1;
  std::vector<std::vector<Turn>> out(turns.size());
  std::vector<std::uint8_t> kinked(turns.size(), 0);
#pragma omp parallel num_threads(threads > 0 ? threads : omp_get_max_threads())
  {
    ExactScratch scratch;
#pragma omp for schedule(dynamic, 16)
    for (std::size_t i = 0; i < turns.size(); ++i) {
      const Turn& t = turns[i];
      out[i] = {t};
      // The search keeps other movers within their own limit; a chain mover it may take past it.
      const bool own = rotation_angle_deg(t.local) <= s.joint_limit_deg[t.organ];
      if (!chain_kind(s.organs[t.organ].kind) || (own && !(t.angle_deg > cfg.bend_step_deg))) continue;
      kinked[i] = own ? 1 : 2;
      const auto rot = turn_rotation(ts.joints, t);
      if (!rot) {
        if (!own) out[i].clear();
        continue;
      }
      std::vector<std::uint32_t> chain = bend_chain(s, cfg, t.organ, cfg.bend_joints, &planned);
      std::reverse(chain.begin(), chain.end());  // proximal first
      const int len = static_cast<int>(chain.size());
      const int want =
          std::clamp(static_cast<int>(std::ceil(rot->deg / cfg.bend_step_deg)), 2, std::max(2, len));
      // The turn at each of the last m joints of the chain, each within its limit, if the bent
      // pose passes.
      const auto attempt = [&](int m, const std::vector<double>& deg) {
        const std::vector<std::uint32_t> c(chain.end() - m, chain.end());
        std::vector<Turn> bent;
        for (int j = 0; j < m; ++j) {
          const Mat3d q = Joints::local_after(ts.joints.joint_frame(c[static_cast<std::size_t>(j)]),
                                              turn_by(rot->axis, deg[static_cast<std::size_t>(j)]));
          if (rotation_angle_deg(q) > s.joint_limit_deg[c[static_cast<std::size_t>(j)]]) return false;
          bent.push_back(Turn{c[static_cast<std::size_t>(j)], q, deg[static_cast<std::size_t>(j)]});
        }
        if (!bend_passes(ts, c, rot->axis, deg, scratch)) return false;
        out[i] = std::move(bent);
        kinked[i] = 0;
        return true;
      };
      // Evenly, about bend_step_deg a joint first, then over more joints (smaller angles, for the
      // limits), then fewer.
      std::vector<int> counts;
      for (int m = want; m <= len; ++m) counts.push_back(m);
      for (int m = std::min(want, len + 1) - 1; m >= 2; --m) counts.push_back(m);
      bool done = false;
      for (int m : counts)
        if ((done = attempt(m, std::vector<double>(static_cast<std::size_t>(m), rot->deg / m)))) break;
      // A turn past the mover's own limit: as near the search's pose as the limits let it, the
      // mover at the most its joint takes, the rest spread evenly above it.
      if (!done && !own) {
        const double room = std::max(0.0, s.joint_limit_deg[t.organ] - ts.joints.angle_deg(t.organ));
        for (int m = 2; m <= len && !done; ++m) {
          std::vector<double> deg(static_cast<std::size_t>(m), (rot->deg - room) / (m - 1));
          deg.back() = room;
          done = attempt(m, deg);
        }
      }
      // Past the mover's own limit and not spread: the turn is not made.
      if (kinked[i] == 2) out[i].clear();
    }
  }
  // In plan order: a spread whose joints an earlier spread took (two branches of one chain, as a
  // pedicel and the next peduncle segment) keeps the search's turn instead.
  std::vector<Turn> all;
  std::vector<std::uint8_t> taken(s.organ_count(), 0);
  for (std::size_t i = 0; i < turns.size(); ++i) {
    if (kinked[i] == 2 && stats) stats->unbent.push_back(turns[i].organ);
    if (out[i].size() > 1) {
      const bool free =
          std::none_of(out[i].begin(), out[i].end(), [&](const Turn& t) { return taken[t.organ] != 0; });
      if (free) {
        for (const Turn& t : out[i]) taken[t.organ] = 1;
      } else {
        const bool own = rotation_angle_deg(turns[i].local) <= s.joint_limit_deg[turns[i].organ];
        out[i] = own ? std::vector<Turn>{turns[i]} : std::vector<Turn>{};
        kinked[i] = own ? 1 : 2;
        if (stats && !own) stats->unbent.push_back(turns[i].organ);
      }
    }
    if (stats && out[i].size() > 1) ++stats->spread, stats->joints += out[i].size();
    if (stats) stats->kinked += kinked[i] == 1;
    all.insert(all.end(), out[i].begin(), out[i].end());
  }
  std::sort(all.begin(), all.end(), [](const Turn& a, const Turn& b) { return a.organ < b.organ; });
  return all;
}

}  // namespace canopy
