#pragma once
/// The exact stage's filters of single triangles (collision/exact.cpp posed_touch), 8 triangles
/// at a time over a pose's triangles kept in lanes (PosedOrgan::tri_lanes): a triangle is near
/// the other organ when its box meets the other's box (given in double, widened by the
/// clearance) and it does not lie beyond the other's OBB by the margin (beyond_obb). Per lane
/// these are the scalar tests' very comparisons and operations in their order, so the same
/// triangles pass (tests/collision/lanes/test_triangle_lanes.cpp holds them equal triangle by
/// triangle). And the float rejections of triangle pairs (triangles_rejected) for one
/// triangle against 8 of the other organ's at once. Host only: nvcc never reads this file.
#include "collision/lanes/lanes8.hpp"
#include "geometry/obb.hpp"
#include "geometry/triangle_reject.hpp"

#include <cmath>
#include <limits>

namespace canopy {

/// A box given in double (lo x y z, hi x y z) as float bounds that a float compares with as with
/// the double: t > hi exactly when t > hi_below (the largest float not above hi), t < lo exactly
/// when t < lo_above (the smallest float not below lo).
struct FloatBounds {
  float lo_above[3], hi_below[3];
  explicit FloatBounds(const double* box) {
    for (int k = 0; k < 3; ++k) {
      float lo = static_cast<float>(box[k]), hi = static_cast<float>(box[k + 3]);
      if (static_cast<double>(lo) < box[k]) lo = std::nextafter(lo, std::numeric_limits<float>::infinity());
      if (static_cast<double>(hi) > box[k + 3])
        hi = std::nextafter(hi, -std::numeric_limits<float>::infinity());
      lo_above[k] = lo, hi_below[k] = hi;
    }
  }
  /// The same bounds for a box whose six doubles hold floats exactly (no rounding to correct).
  static FloatBounds of_floats(const double* box) {
    FloatBounds b;
    for (int k = 0; k < 3; ++k)
      b.lo_above[k] = static_cast<float>(box[k]), b.hi_below[k] = static_cast<float>(box[k + 3]);
    return b;
  }

 private:
  FloatBounds() = default;
};

namespace lanes_detail {
/// Lanes where the box of triangle t of a group (PosedOrgan::tri_lanes) misses `box`:
/// posed_touch's box test (a float box beyond a double box on some axis).
inline I8 boxes_apart8(const float* group, const FloatBounds& box) {
  const auto at = [group](int k) { return load8(group + 8 * k); };
  return (at(9) > box.hi_below[0]) | (at(10) > box.hi_below[1]) | (at(11) > box.hi_below[2]) |
         (at(12) < box.lo_above[0]) | (at(13) < box.lo_above[1]) | (at(14) < box.lo_above[2]);
}
}  // namespace lanes_detail

/// Bit t set where the box of triangle t of a group meets `box` (posed_touch's box test of a
/// triangle pair: b's triangle box against a's widened by the clearance, in double).
inline unsigned boxes_meeting_lanes(const float* group, const FloatBounds& box) {
  return ~lanes_detail::bits8(lanes_detail::boxes_apart8(group, box)) & 0xffu;
}

/// Bit t set where triangle t of a group (PosedOrgan::tri_lanes) is near the other organ: its
/// box meets the other's (posed_touch's box test) and it does not lie beyond the other's OBB by
/// `margin` (beyond_obb), both with their scalar operations in their order, lane by lane.
inline unsigned near_lanes(const float* group, const FloatBounds& box, const Obb& obb, float margin) {
  using namespace lanes_detail;
  const auto at = [group](int k) { return load8(group + 8 * k); };
  I8 far = boxes_apart8(group, box);
  if (bits8(far) == 0xffu) return 0;
  F8 d[3][3];  // corner minus the OBB's centre
  for (int c = 0; c < 3; ++c)
    d[c][0] = at(3 * c) - obb.centre.x, d[c][1] = at(3 * c + 1) - obb.centre.y,
    d[c][2] = at(3 * c + 2) - obb.centre.z;
  for (int k = 0; k < 3; ++k) {
    const Vec3f a = obb.axis[k];
    F8 x[3];
    for (int c = 0; c < 3; ++c) x[c] = d[c][0] * a.x + d[c][1] * a.y + d[c][2] * a.z;
    const float reach = obb.half[k] + margin;
    far |= (min8(x[0], min8(x[1], x[2])) > reach) | (max8(x[0], max8(x[1], x[2])) < -reach);
  }
  return ~bits8(far) & 0xffu;
}

/// Bit t set where triangles_rejected(pt, t, plane of u_t, u_t, margin) holds, u_t the
/// triangle in lane t of a group (PosedOrgan::tri_lanes): its plane made as TrianglePlane::of
/// makes it, then u's plane against t, t's plane against u and the nine edge-cross-edge axes
/// (apart_on_edges), each with the scalar operations in their order; all of them computed for
/// every lane, the answers joined at the end. Only the lanes in `wanted` are answered: where the
/// two planes reject all of those, the edge axes are left uncomputed, and where the axes of t's
/// first edge (or first two) do, the rest (the other lanes' bits are then whatever the tests
/// made so far gave).
inline unsigned rejected_lanes(const TrianglePlane& pt, const Vec3f* t, const float* group, float margin,
                               unsigned wanted = 0xffu) {
  using namespace lanes_detail;
  F8 u[3][3];  // corner, coordinate
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 3; ++k) u[c][k] = load8(group + 8 * (3 * c + k));
  const auto dot_t = [](const F8* n, Vec3f p) { return n[0] * p.x + n[1] * p.y + n[2] * p.z; };
  const auto dot_u = [](const F8* n, const F8* p) { return n[0] * p[0] + n[1] * p[1] + n[2] * p[2]; };
  // u's plane (TrianglePlane::of): n = (u1 - u0) x (u2 - u0), its projections and length.
  F8 e1[3], e2[3], n[3];
  for (int k = 0; k < 3; ++k) e1[k] = u[1][k] - u[0][k], e2[k] = u[2][k] - u[0][k];
  n[0] = e1[1] * e2[2] - e1[2] * e2[1], n[1] = e1[2] * e2[0] - e1[0] * e2[2],
  n[2] = e1[0] * e2[1] - e1[1] * e2[0];
  const F8 d0 = dot_u(n, u[0]), d1 = dot_u(n, u[1]), d2 = dot_u(n, u[2]);
  const F8 u_lo = min8(d0, min8(d1, d2)), u_hi = max8(d0, max8(d1, d2)), u_len = sqrt8(dot_u(n, n));
  // t beyond u's plane (pu.beyond(t)).
  const F8 lim_u = margin * u_len;
  const F8 t0 = dot_t(n, t[0]), t1 = dot_t(n, t[1]), t2 = dot_t(n, t[2]);
  I8 rejected = (min8(t0, min8(t1, t2)) > u_hi + lim_u) | (max8(t0, max8(t1, t2)) < u_lo - lim_u);
  // u beyond t's plane (pt.beyond(u)).
  const float lim_t = margin * pt.length;
  const F8 pn[3] = {splat8(pt.n.x), splat8(pt.n.y), splat8(pt.n.z)};
  const F8 f0 = dot_u(pn, u[0]), f1 = dot_u(pn, u[1]), f2 = dot_u(pn, u[2]);
  rejected |= (min8(f0, min8(f1, f2)) > pt.hi + lim_t) | (max8(f0, max8(f1, f2)) < pt.lo - lim_t);
  if ((wanted & ~bits8(rejected)) == 0) return bits8(rejected);
  // apart_on_edges(t, u): axes et x eu.
  for (int i = 0; i < 3; ++i) {
    const Vec3f et = t[i == 2 ? 0 : i + 1] - t[i];
    for (int j = 0; j < 3; ++j) {
      const int j1 = j == 2 ? 0 : j + 1;
      const F8 eu[3] = {u[j1][0] - u[j][0], u[j1][1] - u[j][1], u[j1][2] - u[j][2]};
      const F8 a[3] = {et.y * eu[2] - et.z * eu[1], et.z * eu[0] - et.x * eu[2], et.x * eu[1] - et.y * eu[0]};
      const F8 p0 = dot_t(a, t[0]), p1 = dot_t(a, t[1]), p2 = dot_t(a, t[2]);
      const F8 q0 = dot_u(a, u[0]), q1 = dot_u(a, u[1]), q2 = dot_u(a, u[2]);
      const F8 p_lo = min8(p0, min8(p1, p2)), p_hi = max8(p0, max8(p1, p2));
      const F8 q_lo = min8(q0, min8(q1, q2)), q_hi = max8(q0, max8(q1, q2));
      const F8 gap = max8(q_lo - p_hi, p_lo - q_hi);
      rejected |= (gap > 0) & (gap > margin * sqrt8(dot_u(a, a)));
    }
    // On the default stand a third of the calls have every wanted lane rejected by t's first
    // edge's three axes, half by its first two edges'.
    if (i < 2 && (wanted & ~bits8(rejected)) == 0) return bits8(rejected);
  }
  return bits8(rejected);
}

}  // namespace canopy
