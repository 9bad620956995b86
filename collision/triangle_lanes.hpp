#pragma once
/// The exact stage's filters of single triangles (collision/exact.cpp posed_touch), 8 triangles
/// at a time over a pose's triangles kept in lanes (PosedOrgan::tri_lanes): a triangle is near
/// the other organ when its box meets the other's box (given in double, widened by the
/// clearance) and it does not lie beyond the other's OBB by the margin (beyond_obb). Per lane
/// these are the scalar tests' very comparisons and operations in their order, so the same
/// triangles pass (tests/collision/test_triangle_lanes.cpp holds them equal triangle by
/// triangle). Host only: nvcc never reads this file.
#include "collision/lanes8.hpp"
#include "geometry/obb.hpp"

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
      if (static_cast<double>(hi) > box[k + 3]) hi = std::nextafter(hi, -std::numeric_limits<float>::infinity());
      lo_above[k] = lo, hi_below[k] = hi;
    }
  }
};

/// Bit t set where triangle t of a group (PosedOrgan::tri_lanes) is near the other organ: its
/// box meets the other's (posed_touch's box test) and it does not lie beyond the other's OBB by
/// `margin` (beyond_obb), both with their scalar operations in their order, lane by lane.
inline unsigned near_lanes(const float* group, const FloatBounds& box, const Obb& obb, float margin) {
  using namespace lanes_detail;
  const auto at = [group](int k) { return load8(group + 8 * k); };
  I8 far = (at(9) > box.hi_below[0]) | (at(10) > box.hi_below[1]) | (at(11) > box.hi_below[2]) | (at(12) < box.lo_above[0]) |
           (at(13) < box.lo_above[1]) | (at(14) < box.lo_above[2]);
  if (bits8(far) == 0xffu) return 0;
  F8 d[3][3];  // corner minus the OBB's centre
  for (int c = 0; c < 3; ++c)
    d[c][0] = at(3 * c) - obb.centre.x, d[c][1] = at(3 * c + 1) - obb.centre.y, d[c][2] = at(3 * c + 2) - obb.centre.z;
  for (int k = 0; k < 3; ++k) {
    const Vec3f a = obb.axis[k];
    F8 x[3];
    for (int c = 0; c < 3; ++c) x[c] = d[c][0] * a.x + d[c][1] * a.y + d[c][2] * a.z;
    const float reach = obb.half[k] + margin;
    const F8 lo = x[1] < x[2] ? x[1] : x[2], hi = x[1] > x[2] ? x[1] : x[2];
    far |= ((x[0] < lo ? x[0] : lo) > reach) | ((x[0] > hi ? x[0] : hi) < -reach);
  }
  return ~bits8(far) & 0xffu;
}

}  // namespace canopy
