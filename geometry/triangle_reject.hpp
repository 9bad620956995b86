#pragma once
/// Quick, conservative float rejections before the exact triangle test, shared by both backends
/// (CANOPY_HD): a pair they reject lies farther apart than the exact test's clearance, so they
/// change no answer, only how much of the double-precision test runs.
#include "geometry/hd.hpp"
#include "geometry/obb.hpp"
#include "geometry/vec.hpp"

namespace canopy {

/// 10 µm: far above the float rounding of a plane or edge-axis test on plant-frame coordinates
/// (about 1e-7 m); the rejections use clearance + this as their margin.
inline constexpr float kRejectSlack = 1e-5f;

/// A quick, conservative rejection before the exact triangle test, on the vertices that test
/// receives: a separating-axis test in float along a triangle's (unnormalised) normal n. The
/// triangle's own projections n . p_k span [lo, hi] (a point when n is exact, an interval when
/// a sliver's normal is not), the other's must lie wholly beyond it by more than `margin` x |n|.
/// Any axis separating the two by that much keeps them more than `margin` apart, and the float
/// rounding (about 1e-7 m at plant scale) is far below the margin's slack over the clearance, so
/// the exact test would have rejected them too.
struct TrianglePlane {
  Vec3f n;
  float lo = 0, hi = 0, length = 0;  // length: |n|
  CANOPY_HD static TrianglePlane of(Vec3f p0, Vec3f p1, Vec3f p2) {
    TrianglePlane t;
    t.n = cross(p1 - p0, p2 - p0);
    const float d0 = dot(t.n, p0), d1 = dot(t.n, p1), d2 = dot(t.n, p2);
    t.lo = min_f(d0, min_f(d1, d2)), t.hi = max_f(d0, max_f(d1, d2));
    t.length = sqrtf(dot(t.n, t.n));
    return t;
  }
  /// Whether q lies beyond the plane by more than `margin` (margin x |n| along n).
  CANOPY_HD bool beyond(const Vec3f* q, float margin) const {
    const float lim = margin * length;
    const float d0 = dot(n, q[0]), d1 = dot(n, q[1]), d2 = dot(n, q[2]);
    return min_f(d0, min_f(d1, d2)) > hi + lim || max_f(d0, max_f(d1, d2)) < lo - lim;
  }
};

/// The same kind of float rejection on the nine axes across an edge of t and an edge of u (their
/// cross products; any axis separates by the separating-axis theorem): true when the two
/// triangles' projections lie more than `margin` x |axis| apart on one of them. The float rounding
/// of a projection (a few 1e-7 |axis| at plant-frame coordinates of metres) is far below the
/// margin's slack, so a pair rejected here is farther apart than the exact test's clearance.
CANOPY_HD inline bool apart_on_edges(const Vec3f* t, const Vec3f* u, float margin) {
  for (int i = 0; i < 3; ++i) {
    const Vec3f et = t[i == 2 ? 0 : i + 1] - t[i];
    for (int j = 0; j < 3; ++j) {
      const Vec3f n = cross(et, u[j == 2 ? 0 : j + 1] - u[j]);
      const float t0 = dot(n, t[0]), t1 = dot(n, t[1]), t2 = dot(n, t[2]);
      const float u0 = dot(n, u[0]), u1 = dot(n, u[1]), u2 = dot(n, u[2]);
      const float t_lo = min_f(t0, min_f(t1, t2)), t_hi = max_f(t0, max_f(t1, t2));
      const float u_lo = min_f(u0, min_f(u1, u2)), u_hi = max_f(u0, max_f(u1, u2));
      const float gap = max_f(u_lo - t_hi, t_lo - u_hi);
      if (gap > 0 && gap > margin * sqrtf(dot(n, n))) return true;
    }
  }
  return false;
}

/// Whether triangle t lies beyond OBB o's slab along one of o's axes by more than `margin`
/// (clearance + kRejectSlack): then it is farther than the clearance from everything inside o,
/// and o holds every vertex of its organ (with the bounds' slack, so every triangle too), so no
/// triangle of that organ meets t. A filter of single triangles before the pair tests: the box
/// filters pass triangles near the other organ's axis-aligned box, which for a tilted flat
/// leaflet is far larger than its OBB. The float rounding of the projections (about 1e-7 of
/// plant-frame coordinates) is far below the margin's slack, so it changes no answer.
CANOPY_HD inline bool beyond_obb(const Vec3f* t, const Obb& o, float margin) {
  const Vec3f d0 = t[0] - o.centre, d1 = t[1] - o.centre, d2 = t[2] - o.centre;
  for (int k = 0; k < 3; ++k) {
    const float x0 = dot(d0, o.axis[k]), x1 = dot(d1, o.axis[k]), x2 = dot(d2, o.axis[k]);
    const float reach = o.half[k] + margin;
    if (min_f(x0, min_f(x1, x2)) > reach || max_f(x0, max_f(x1, x2)) < -reach) return true;
  }
  return false;
}

/// Whether the float tests reject the pair (t, u) at `margin` (clearance + kRejectSlack): u
/// beyond t's plane, t beyond u's, or apart on an edge-edge axis.
CANOPY_HD inline bool triangles_rejected(const TrianglePlane& pt, const Vec3f* t, const TrianglePlane& pu,
                                         const Vec3f* u, float margin) {
  return pu.beyond(t, margin) || pt.beyond(u, margin) || apart_on_edges(t, u, margin);
}

}  // namespace canopy
