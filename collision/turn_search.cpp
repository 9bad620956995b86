#include "collision/turn_search.hpp"

#include "collision/contacts.hpp"
#include "geometry/obb.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace canopy {
namespace {

constexpr double kRad = std::numbers::pi / 180;

Vec3d unit(Vec3f v) { return normalized(to_double(v)); }

}  // namespace

std::optional<Turn> TurnSearch::find(std::uint32_t mover, const std::vector<std::pair<std::int32_t, std::int32_t>>& met,
                                     ExactScratch& scratch) const {
  const Stand& s = stand;
  const std::int32_t plant = s.organs[mover].plant;
  const std::uint32_t end = joints.subtree_end(mover);
  const Vec3d joint = to_double(s.transforms[mover].t);
  const double limit = s.joint_limit_deg[mover];
  const auto box = [&](std::int32_t k) {
    const OrganRecord& r = s.organs[static_cast<std::size_t>(k)];
    return lib.get(r.prototype, r.lod).box;
  };
  const auto offset_to = [&](std::int32_t k) {  // carries organ k's plant frame into the mover's
    const std::int32_t p = s.organs[static_cast<std::size_t>(k)].plant;
    return p == plant ? Vec3f{0, 0, 0} : plant_offset(s, plant, p);
  };

  // The organs that move (those taking part in detection) and the ones they must clear.
  std::vector<std::int32_t> moving, others;
  for (std::uint32_t k = mover; k < end; ++k)
    if (collide[static_cast<std::size_t>(s.organs[k].kind)]) moving.push_back(static_cast<std::int32_t>(k));
  for (const auto& [x, y] : met) others.push_back(y);
  std::sort(others.begin(), others.end());
  others.erase(std::unique(others.begin(), others.end()), others.end());
  std::vector<Obb> other_box;
  for (std::int32_t y : others) other_box.push_back(make_obb(s.transforms[static_cast<std::size_t>(y)], box(y), clearance));

  // Axis that swings the contact organs straight away from what they met.
  Vec3d away{0, 0, 0};
  for (const auto& [x, y] : met) {
    const Obb ox = make_obb(s.transforms[static_cast<std::size_t>(x)], box(x), 0);
    const Obb oy = make_obb(s.transforms[static_cast<std::size_t>(y)], box(y), 0);
    const Vec3d p = to_double(ox.centre), q = to_double(oy.centre + offset_to(y));
    const Vec3d a = cross(p - joint, p - q);
    if (length(a) > 1e-12) away = away + normalized(a);
  }
  const Affine3f& tm = s.transforms[mover];
  std::vector<Vec3d> axes;
  if (length(away) > 1e-9) axes.push_back(normalized(away));
  const Vec3d l = unit(tm.c1), u = unit(tm.c2);
  for (Vec3d a : {l, l * -1.0, u, u * -1.0})
    if (length(a) > 0.5) axes.push_back(a);

  // Whether the moving organs, turned by `r` about the joint, clear every organ met.
  const auto separated = [&](const Motion& turn) {
    for (std::int32_t x : moving) {
      const Affine3f tx = apply(turn, s.transforms[static_cast<std::size_t>(x)]);
      const Obb ox = make_obb(tx, box(x), clearance);
      for (std::size_t i = 0; i < others.size(); ++i) {
        const std::int32_t y = others[i];
        if (adjacent(s.organs[static_cast<std::size_t>(x)], x, s.organs[static_cast<std::size_t>(y)], y)) continue;
        if (!obb_overlap(ox, other_box[i], offset_to(y))) continue;
        if (config.level == ContactLevel::organ) return false;
        const Affine3f& ty = s.transforms[static_cast<std::size_t>(y)];
        const bool touch = x < y ? organs_touch_at(s, lib, x, tx, y, ty, clearance, scratch)
                                 : organs_touch_at(s, lib, y, ty, x, tx, clearance, scratch);
        if (touch) return false;
      }
    }
    return true;
  };
  // A turn by `deg` about axis a: feasible when within the joint limit and separating.
  const auto attempt = [&](const Vec3d& a, double deg, Mat3d& local) {
    const Mat3d r = axis_angle(a, deg * kRad);
    local = joints.local_after(mover, r);
    if (rotation_angle_deg(local) > limit) return false;
    return separated(rotation_about(joint, r));
  };

  const double step = std::max(config.scan_step_deg, config.angle_tolerance_deg);
  const double reach = std::min(180.0, limit + joints.angle_deg(mover));  // no turn beyond this can stay in the limit
  double lo = 0;
  for (double hi = std::min(step, reach); lo < reach; lo = hi, hi = std::min(hi + step, reach)) {
    for (const Vec3d& a : axes) {
      Mat3d local;
      if (!attempt(a, hi, local)) continue;
      // Bisect (lo, hi] on this axis down to the tolerance; hi stays feasible.
      double b_lo = lo, b_hi = hi;
      Mat3d best = local;
      while (b_hi - b_lo > config.angle_tolerance_deg) {
        const double mid = 0.5 * (b_lo + b_hi);
        Mat3d m;
        if (attempt(a, mid, m)) b_hi = mid, best = m;
        else b_lo = mid;
      }
      return Turn{mover, best, b_hi};
    }
  }
  return std::nullopt;
}

}  // namespace canopy
