#pragma once
/// The exact test with a clearance: whether two closed triangles come within a distance of each
/// other, on the orientation predicates and the canonical order of geometry/triangle_test.hpp
/// (the same answer for any vertex order, either argument order, and on either backend), with
/// quick rejections on the 11 axes where separated triangles show their gap. Shared by the CPU
/// and CUDA backends.
#include "geometry/triangle_test.hpp"

namespace canopy {

/// Squared distance between closed segments [p1, q1] and [p2, q2] (Ericsson §5.1.9).
CANOPY_HD_OUTLINE inline double segment_segment_dist2(D3 p1, D3 q1, D3 p2, D3 q2) {
  const D3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = dot(d1, d1), e = dot(d2, d2), f = dot(d2, r);
  double s = 0, t = 0;
  if (a == 0 && e == 0) {
    s = t = 0;
  } else if (a == 0) {
    s = 0;
    t = min_d(max_d(f / e, 0.0), 1.0);
  } else {
    const double c = dot(d1, r);
    if (e == 0) {
      t = 0;
      s = min_d(max_d(-c / a, 0.0), 1.0);
    } else {
      const double b = dot(d1, d2), denom = a * e - b * b;
      s = denom != 0 ? min_d(max_d((b * f - c * e) / denom, 0.0), 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0;
        s = min_d(max_d(-c / a, 0.0), 1.0);
      } else if (t > 1) {
        t = 1;
        s = min_d(max_d((b - c) / a, 0.0), 1.0);
      }
    }
  }
  const D3 c1 = p1 + d1 * s, c2 = p2 + d2 * t, w = c1 - c2;
  return dot(w, w);
}

/// Squared distance from p to the closed triangle t (Ericsson §5.1.5); a degenerate triangle
/// counts as its edges.
CANOPY_HD_OUTLINE inline double point_triangle_dist2(D3 p, const D3 t[3]) {
  const D3 a = t[0], b = t[1], c = t[2];
  const D3 n = cross(b - a, c - a);
  if (n.x == 0 && n.y == 0 && n.z == 0)
    return min_d(segment_segment_dist2(p, p, a, b),
                 min_d(segment_segment_dist2(p, p, b, c), segment_segment_dist2(p, p, c, a)));
  const D3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  D3 q;
  if (d1 <= 0 && d2 <= 0) q = a;
  else {
    const D3 bp = p - b;
    const double d3v = dot(ab, bp), d4 = dot(ac, bp);
    const D3 cp = p - c;
    const double d5 = dot(ab, cp), d6 = dot(ac, cp);
    const double vc = d1 * d4 - d3v * d2, vb = d5 * d2 - d1 * d6, va = d3v * d6 - d5 * d4;
    if (d3v >= 0 && d4 <= d3v) q = b;
    else if (vc <= 0 && d1 >= 0 && d3v <= 0) q = a + ab * (d1 / (d1 - d3v));
    else if (d6 >= 0 && d5 <= d6) q = c;
    else if (vb <= 0 && d2 >= 0 && d6 <= 0) q = a + ac * (d2 / (d2 - d6));
    else if (va <= 0 && (d4 - d3v) >= 0 && (d5 - d6) >= 0)
      q = b + (c - b) * ((d4 - d3v) / ((d4 - d3v) + (d5 - d6)));
    else {
      const double denom = 1.0 / (va + vb + vc);
      q = a + ab * (vb * denom) + ac * (vc * denom);
    }
  }
  const D3 w = p - q;
  return dot(w, w);
}

/// Whether every vertex of u lies farther than `clearance` from the plane of t, all on one side
/// (then no point of u comes that close to t). A quick rejection with a relative margin, so it
/// never decides a case the full test would answer otherwise beyond rounding.
CANOPY_HD inline bool beyond_plane(const D3 t[3], const D3 u[3], double clearance) {
  const D3 n = cross(t[1] - t[0], t[2] - t[0]);
  const double nn = dot(n, n);
  if (!(nn > 0)) return false;
  // d > |n| k for all three (or < -|n| k), compared squared: no square root.
  const double k = clearance * (1 + 1e-9) + 1e-12, lim2 = nn * k * k;
  const double d0 = dot(n, u[0] - t[0]), d1 = dot(n, u[1] - t[0]), d2 = dot(n, u[2] - t[0]);
  const bool above = d0 > 0 && d1 > 0 && d2 > 0, below = d0 < 0 && d1 < 0 && d2 < 0;
  return (above || below) && d0 * d0 > lim2 && d1 * d1 > lim2 && d2 * d2 > lim2;
}

/// Whether, on some axis across an edge of t and an edge of u (their cross product), the two
/// triangles' projections lie more than `clearance` apart; then so do the triangles (the
/// separating-axis theorem: the distance is at least the gap along any unit axis). Together with
/// beyond_plane these are the 11 axes on which two separated triangles' closest features show
/// their gap (face-vertex on a normal, edge-edge on a cross product), so most pairs that do not
/// come near are rejected here before the distance routines; the same margin as beyond_plane, so
/// it never rejects a pair the full test would accept beyond rounding.
CANOPY_HD inline bool apart_on_edge_axes(const D3 t[3], const D3 u[3], double clearance) {
  const double k = clearance * (1 + 1e-9) + 1e-12;
  for (int i = 0; i < 3; ++i) {
    const D3 et = t[(i + 1) % 3] - t[i];
    for (int j = 0; j < 3; ++j) {
      const D3 n = cross(et, u[(j + 1) % 3] - u[j]);
      const double nn = dot(n, n);
      if (!(nn > 0)) continue;
      // Projections relative to t[0] (t's own edge i projects to one value).
      const double t1 = dot(n, t[1] - t[0]), t2 = dot(n, t[2] - t[0]);
      const double u0 = dot(n, u[0] - t[0]), u1 = dot(n, u[1] - t[0]), u2 = dot(n, u[2] - t[0]);
      const double t_lo = min_d(0.0, min_d(t1, t2)), t_hi = max_d(0.0, max_d(t1, t2));
      const double u_lo = min_d(u0, min_d(u1, u2)), u_hi = max_d(u0, max_d(u1, u2));
      const double gap = max_d(u_lo - t_hi, t_lo - u_hi);
      if (gap > 0 && gap * gap > nn * k * k) return true;
    }
  }
  return false;
}

/// Whether two closed triangles come within `clearance` of each other (intersecting counts).
/// `likely_touching` (a pair that touched at a nearby pose) only changes the order of the work:
/// the intersection test first, the quick rejections after; the answer is the same.
CANOPY_HD_OUTLINE inline bool triangles_within(const Vec3f* pa, const Vec3f* pb, double clearance,
                                               bool likely_touching = false) {
  D3 a[3], b[3];
  const D3 *t, *u;
  canonical_pair(pa, pb, a, b, t, u);
  if (likely_touching && triangles_intersect_canonical(t, u)) return true;
  if (beyond_plane(t, u, clearance) || beyond_plane(u, t, clearance) || apart_on_edge_axes(t, u, clearance))
    return false;
  if (!likely_touching && triangles_intersect_canonical(t, u)) return true;
  const double c2 = clearance * clearance;
  for (int i = 0; i < 3; ++i) {
    if (point_triangle_dist2(t[i], u) <= c2 || point_triangle_dist2(u[i], t) <= c2) return true;
    for (int j = 0; j < 3; ++j)
      if (segment_segment_dist2(t[i], t[(i + 1) % 3], u[j], u[(j + 1) % 3]) <= c2) return true;
  }
  return false;
}

}  // namespace canopy
