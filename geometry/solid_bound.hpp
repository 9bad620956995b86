#pragma once
/// A quick, conservative rejection of two solid organs (capped cylinders, spheres) before the
/// host's exact test (collision/exact.cpp; the device's warp test measured faster without it,
/// cuda/organ_pair_test.cuh): each solid, its mesh and what its mesh encloses lie inside a
/// capsule (a segment and a radius; a ball for a sphere), and two capsules farther apart than the
/// clearance plus a slack far above every rounding keep the organs so too. It changes no answer,
/// only how many pairs are posed: on the default 1,000-plant stand half of the organ pairs whose
/// OBBs overlap without touching are an internode beside a peduncle of the same plant, and every
/// one of them is rejected here.
///
/// Segment distance: Ericson, Real-Time Collision Detection §5.1.9, made a lower bound here (the
/// least distance of two segments lies at an end of one of them unless both closest points are
/// inside, where it is their lines' distance), so rounding never makes the organs seem farther
/// apart than they are.
#include "geometry/hd.hpp"
#include "geometry/organ_kind.hpp"
#include "geometry/triangle_distance.hpp"
#include "geometry/triangle_test.hpp"
#include "geometry/vec.hpp"

namespace canopy {

/// The points p + s u (s in [0, 1]) widened by `radius`; `size` bounds the magnitudes that the
/// posed vertices are computed from (their float rounding is far below 1e-5 of it).
struct Capsule {
  D3 p{0, 0, 0}, u{0, 0, 0};
  double radius = 0, size = 0;
};

namespace solid_bound_detail {

CANOPY_HD inline double norm(D3 a) { return sqrt(dot(a, a)); }

/// Distance from x to the segment p + s u, s in [0, 1] (to a point of it: never below the least).
CANOPY_HD inline double point_segment_distance(D3 x, D3 p, D3 u) {
  return sqrt(segment_segment_dist2(x, x, p, p + u));
}

/// sqrt of Gershgorin's bound on the largest eigenvalue of a Gram matrix: a bound on the
/// largest stretch of the map whose columns made it (its spectral norm), exact for orthogonal
/// columns and never below it for any.
CANOPY_HD inline double stretch_bound(const double* g, int n) {
  double most = 0;
  for (int i = 0; i < n; ++i) {
    double row = 0;
    for (int j = 0; j < n; ++j) row += i == j ? g[i * n + j] : fabs(g[i * n + j]);
    most = max_d(most, row);
  }
  return sqrt(most);
}

}  // namespace solid_bound_detail

/// A lower bound on the distance between segments p + s u and q + t v (s, t in [0, 1]), within
/// double rounding. Where the lines are all but parallel (sin < 1e-5) the ends' distances,
/// which then exceed the least by at most 2 (|u| + |v|) sin, less that.
CANOPY_HD inline double segments_distance_bound(D3 p, D3 u, D3 q, D3 v) {
  using solid_bound_detail::point_segment_distance;
  double best = min_d(min_d(point_segment_distance(p, q, v), point_segment_distance(p + u, q, v)),
                      min_d(point_segment_distance(q, p, u), point_segment_distance(q + v, p, u)));
  const double uu = dot(u, u), vv = dot(v, v);
  if (!(uu > 0 && vv > 0)) return best;  // a point: its distance to the other is at an end
  const D3 n = cross(u, v);
  const double nn = dot(n, n);
  if (!(nn > 1e-10 * uu * vv)) return max_d(0.0, best - 2 * (sqrt(uu) + sqrt(vv)) * sqrt(nn / (uu * vv)));
  // The lines' closest points p + s u, q + t v; inside both segments the least distance may be
  // the lines' own. The margins are far above the rounding of s and t (about 4 ulp of |r| / |u|
  // and |r| / |v|, over sin^2): a lower bound where they would fall just outside.
  const D3 r = q - p;
  const double b = dot(u, v), c = dot(u, r), f = dot(v, r);
  const double s = (c * vv - b * f) / nn, t = (b * c - uu * f) / nn;
  const double rr = dot(r, r), sin2 = nn / (uu * vv);
  const double ws = 1e-12 + 1e-14 * (1 + sqrt(rr / uu)) / sin2,
               wt = 1e-12 + 1e-14 * (1 + sqrt(rr / vv)) / sin2;
  if (s >= -ws && s <= 1 + ws && t >= -wt && t <= 1 + wt) best = min_d(best, fabs(dot(r, n)) / sqrt(nn));
  return best;
}

/// The capsule of a solid organ at transform m moved by d (into another plant's frame), or
/// false for organs that are not solids. A capped cylinder's mesh (prototype: unit circles at
/// x = 0 and 1) lies within its axis segment t + s c0 widened by the stretch of (c1, c2); a
/// sphere's (unit sphere about x = 1) within the ball about t + c0 of the stretch of all three.
CANOPY_HD inline bool solid_capsule(PrototypeKind k, const Affine3f& m, Vec3f d, Capsule& c) {
  using solid_bound_detail::norm;
  if (!is_solid(k)) return false;
  const D3 col[3] = {d3(m.c0), d3(m.c1), d3(m.c2)};
  const D3 t = d3(m.t) + d3(d);
  const int first = k == PrototypeKind::cylinder ? 1 : 0, n = 3 - first;
  double g[9];
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) g[i * n + j] = dot(col[first + i], col[first + j]);
  c.radius = solid_bound_detail::stretch_bound(g, n);
  if (k == PrototypeKind::cylinder) {
    c.p = t, c.u = col[0];
  } else {
    c.p = t + col[0], c.u = D3{0, 0, 0};
  }
  c.size = norm(d3(m.t)) + norm(d3(d)) + norm(col[0]) + norm(col[1]) + norm(col[2]);
  return true;
}

/// Relative and absolute slack of solids_apart: 1e-5 of the magnitudes the vertices come from
/// (their float rounding is below 1e-6 of it) and 2 µm, above the 1 µm within which docs/design.md
/// lets the exact answer go either way, so a pair rejected here is one the exact test rejects.
inline constexpr double kSolidRelSlack = 1e-5;
inline constexpr double kSolidAbsSlack = 2e-6;

/// Whether organs a (prototype ka, transform ta) and b (kb, tb, moved by db into a's plant
/// frame) are both solids whose capsules lie more than `clearance` plus the slack apart: then
/// neither their triangles nor what one encloses come within the clearance of the other. False
/// (test them) for any other pair, and for non-finite transforms.
CANOPY_HD inline bool solids_apart(PrototypeKind ka, const Affine3f& ta, PrototypeKind kb, const Affine3f& tb,
                                   Vec3f db, float clearance) {
  Capsule a, b;
  if (!solid_capsule(ka, ta, Vec3f{0, 0, 0}, a) || !solid_capsule(kb, tb, db, b)) return false;
  const double reach = a.radius + b.radius + static_cast<double>(clearance) +
                       kSolidRelSlack * (a.size + b.size) + kSolidAbsSlack;
  return segments_distance_bound(a.p, a.u, b.p, b.u) > reach;
}

}  // namespace canopy
