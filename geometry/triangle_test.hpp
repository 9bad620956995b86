#pragma once
/// The exact test: closed triangle-triangle intersection and point-in-convex-solid (the
/// distance within a clearance is in geometry/triangle_distance.hpp), on orientation predicates
/// evaluated in double from float inputs (so answers agree with exact arithmetic wherever gaps
/// or overlaps exceed about 1e-12 m at plant scale). Every entry point first puts its arguments
/// in a canonical order (vertices sorted, triangles sorted), so the answer is bit for bit the
/// same for any vertex order, either argument order, and on either backend (compiled with
/// -ffp-contract=off / --fmad=false). Shared by the CPU and CUDA backends.
#include "geometry/hd.hpp"
#include "geometry/vec.hpp"

namespace canopy {

struct D3 {
  double x, y, z;
};
/// min and max of finite doubles, inline on every compiler (libm's fmin/fmax are calls on the
/// host, for NaN semantics the finite inputs here never need).
CANOPY_HD inline double min_d(double a, double b) { return a < b ? a : b; }
CANOPY_HD inline double max_d(double a, double b) { return a > b ? a : b; }
CANOPY_HD inline D3 d3(Vec3f v) { return {v.x, v.y, v.z}; }
CANOPY_HD inline D3 operator-(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
CANOPY_HD inline D3 operator+(D3 a, D3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
CANOPY_HD inline D3 operator*(D3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
CANOPY_HD inline double dot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
CANOPY_HD inline D3 cross(D3 a, D3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
CANOPY_HD inline bool less(D3 a, D3 b) {
  return a.x < b.x || (a.x == b.x && (a.y < b.y || (a.y == b.y && a.z < b.z)));
}
CANOPY_HD inline bool same(D3 a, D3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

/// det[b - a, c - a, d - a]: positive when d lies on the side of plane (a, b, c) that
/// (b - a) x (c - a) points to.
CANOPY_HD inline double orient3d(D3 a, D3 b, D3 c, D3 d) {
  const D3 ba = b - a, ca = c - a, da = d - a;
  return ba.x * (ca.y * da.z - ca.z * da.y) - ba.y * (ca.x * da.z - ca.z * da.x) +
         ba.z * (ca.x * da.y - ca.y * da.x);
}

struct P2 {
  double u, v;
};
CANOPY_HD inline double orient2d(P2 a, P2 b, P2 c) {
  return (b.u - a.u) * (c.v - a.v) - (b.v - a.v) * (c.u - a.u);
}
CANOPY_HD inline int sign(double x) { return (x > 0) - (x < 0); }

/// Drops the coordinate `axis` (0, 1, 2).
CANOPY_HD inline P2 project(D3 p, int axis) {
  return axis == 0 ? P2{p.y, p.z} : axis == 1 ? P2{p.z, p.x} : P2{p.x, p.y};
}
CANOPY_HD inline int dominant_axis(D3 n) {
  const double ax = fabs(n.x), ay = fabs(n.y), az = fabs(n.z);
  return ax >= ay && ax >= az ? 0 : ay >= az ? 1 : 2;
}

/// p on closed segment [a, b], given that the three are collinear.
CANOPY_HD inline bool on_segment_2d(P2 a, P2 b, P2 p) {
  return min_d(a.u, b.u) <= p.u && p.u <= max_d(a.u, b.u) && min_d(a.v, b.v) <= p.v && p.v <= max_d(a.v, b.v);
}

/// Closed segments [a, b] and [c, d] in the plane meet.
CANOPY_HD inline bool segments_2d(P2 a, P2 b, P2 c, P2 d) {
  const int o1 = sign(orient2d(a, b, c)), o2 = sign(orient2d(a, b, d));
  const int o3 = sign(orient2d(c, d, a)), o4 = sign(orient2d(c, d, b));
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  if (o1 == 0 && on_segment_2d(a, b, c)) return true;
  if (o2 == 0 && on_segment_2d(a, b, d)) return true;
  if (o3 == 0 && on_segment_2d(c, d, a)) return true;
  if (o4 == 0 && on_segment_2d(c, d, b)) return true;
  return false;
}

/// p in the closed triangle (a, b, c) of the plane; a degenerate triangle counts as its edges.
CANOPY_HD inline bool point_in_triangle_2d(P2 p, P2 a, P2 b, P2 c) {
  if (orient2d(a, b, c) == 0)
    return segments_2d(a, b, p, p) || segments_2d(b, c, p, p) || segments_2d(c, a, p, p);
  const int s1 = sign(orient2d(a, b, p)), s2 = sign(orient2d(b, c, p)), s3 = sign(orient2d(c, a, p));
  return !((s1 < 0 || s2 < 0 || s3 < 0) && (s1 > 0 || s2 > 0 || s3 > 0));
}

/// Closed triangles in a common plane (projected along `axis`) meet.
CANOPY_HD_OUTLINE inline bool triangles_2d(const D3 t[3], const D3 u[3], int axis) {
  P2 a[3], b[3];
  for (int i = 0; i < 3; ++i) a[i] = project(t[i], axis), b[i] = project(u[i], axis);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (segments_2d(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3])) return true;
  return point_in_triangle_2d(a[0], b[0], b[1], b[2]) || point_in_triangle_2d(b[0], a[0], a[1], a[2]);
}

/// Closed segments [a, b] and [c, d] in space meet (degenerate segments are points).
CANOPY_HD_OUTLINE inline bool segments_3d(D3 a, D3 b, D3 c, D3 d) {
  if (orient3d(a, b, c, d) != 0) return false;  // skew
  // Coplanar: project along the normal of their plane, or of any plane holding them.
  D3 n = cross(b - a, d - c);
  if (n.x == 0 && n.y == 0 && n.z == 0) n = cross(b - a, c - a);
  if (n.x == 0 && n.y == 0 && n.z == 0) n = cross(d - c, a - c);
  if (n.x == 0 && n.y == 0 && n.z == 0) {
    // All four on one line (or coincident): compare intervals along the coordinate of largest
    // spread, on which distinct points of the line always differ.
    D3 lo = a, hi = a;
    const D3 ps[3] = {b, c, d};
    for (const D3& p : ps) {
      lo = {min_d(lo.x, p.x), min_d(lo.y, p.y), min_d(lo.z, p.z)};
      hi = {max_d(hi.x, p.x), max_d(hi.y, p.y), max_d(hi.z, p.z)};
    }
    const D3 ext = hi - lo;
    const int k = ext.x >= ext.y && ext.x >= ext.z ? 0 : ext.y >= ext.z ? 1 : 2;
    const double ak = k == 0 ? a.x : k == 1 ? a.y : a.z, bk = k == 0 ? b.x : k == 1 ? b.y : b.z;
    const double ck = k == 0 ? c.x : k == 1 ? c.y : c.z, dk = k == 0 ? d.x : k == 1 ? d.y : d.z;
    return max_d(min_d(ak, bk), min_d(ck, dk)) <= min_d(max_d(ak, bk), max_d(ck, dk));
  }
  const int axis = dominant_axis(n);
  return segments_2d(project(a, axis), project(b, axis), project(c, axis), project(d, axis));
}

/// Closed segment [a, b], lying in the plane of triangle t (normal n, not zero), meets t.
CANOPY_HD_OUTLINE inline bool segment_triangle_in_plane(D3 a, D3 b, const D3 t[3], D3 n) {
  const int axis = dominant_axis(n);
  const P2 pa = project(a, axis), pb = project(b, axis);
  P2 q[3];
  for (int i = 0; i < 3; ++i) q[i] = project(t[i], axis);
  if (point_in_triangle_2d(pa, q[0], q[1], q[2]) || point_in_triangle_2d(pb, q[0], q[1], q[2])) return true;
  for (int i = 0; i < 3; ++i)
    if (segments_2d(pa, pb, q[i], q[(i + 1) % 3])) return true;
  return false;
}

/// Closed segment [a, b] meets the closed triangle t, given t's normal n = (t1 - t0) x (t2 - t0)
/// when not zero and the orientations sa, sb of a and b against t's plane (orient3d(t0, t1, t2, .)):
/// the values segment_triangle computes, passed in where the caller has them already.
CANOPY_HD inline bool segment_triangle_sided(D3 a, D3 b, const D3 t[3], D3 n, double sa, double sb) {
  if ((sa > 0 && sb > 0) || (sa < 0 && sb < 0)) return false;
  if (sa == 0 && sb == 0) return segment_triangle_in_plane(a, b, t, n);
  // The segment crosses or touches the plane: does its line pass through the closed triangle?
  const int s1 = sign(orient3d(a, b, t[0], t[1])), s2 = sign(orient3d(a, b, t[1], t[2])),
            s3 = sign(orient3d(a, b, t[2], t[0]));
  return !((s1 < 0 || s2 < 0 || s3 < 0) && (s1 > 0 || s2 > 0 || s3 > 0));
}

/// Closed segment [a, b] meets the closed triangle t (which may be degenerate).
CANOPY_HD_OUTLINE inline bool segment_triangle(D3 a, D3 b, const D3 t[3]) {
  const D3 n = cross(t[1] - t[0], t[2] - t[0]);
  if (n.x == 0 && n.y == 0 && n.z == 0)  // degenerate triangle: its edges
    return segments_3d(a, b, t[0], t[1]) || segments_3d(a, b, t[1], t[2]) || segments_3d(a, b, t[2], t[0]);
  return segment_triangle_sided(a, b, t, n, orient3d(t[0], t[1], t[2], a), orient3d(t[0], t[1], t[2], b));
}

/// Sorts a triangle's vertices (lexicographically): the canonical order.
CANOPY_HD inline void sort3(D3 t[3]) {
  if (less(t[1], t[0])) {
    const D3 x = t[0];
    t[0] = t[1];
    t[1] = x;
  }
  if (less(t[2], t[1])) {
    const D3 x = t[1];
    t[1] = t[2];
    t[2] = x;
  }
  if (less(t[1], t[0])) {
    const D3 x = t[0];
    t[0] = t[1];
    t[1] = x;
  }
}
CANOPY_HD inline bool triangle_less(const D3 a[3], const D3 b[3]) {
  for (int i = 0; i < 3; ++i) {
    if (less(a[i], b[i])) return true;
    if (less(b[i], a[i])) return false;
  }
  return false;
}

/// The canonical order of a triangle pair: each triangle's vertices sorted, then the smaller
/// triangle first (t), so every vertex order and argument order computes the same thing.
CANOPY_HD inline void canonical_pair(const Vec3f* pa, const Vec3f* pb, D3 a[3], D3 b[3], const D3*& t,
                                     const D3*& u) {
  for (int i = 0; i < 3; ++i) a[i] = d3(pa[i]), b[i] = d3(pb[i]);
  sort3(a);
  sort3(b);
  t = a, u = b;
  if (triangle_less(b, a)) t = b, u = a;
}

/// Whether two closed triangles meet (touching counts), on a pair in canonical order
/// (canonical_pair's t and u); triangles_intersect below takes any order.
CANOPY_HD_OUTLINE inline bool triangles_intersect_canonical(const D3* t, const D3* u) {
  const D3 nt = cross(t[1] - t[0], t[2] - t[0]), nu = cross(u[1] - u[0], u[2] - u[0]);
  const bool dt = nt.x == 0 && nt.y == 0 && nt.z == 0, du = nu.x == 0 && nu.y == 0 && nu.z == 0;
  // su: u's vertices against t's plane; st: t's against u's (what segment_triangle computes).
  double su[3] = {0, 0, 0}, st[3] = {0, 0, 0};
  if (!dt) {  // quick rejection: u wholly on one side of t's plane
    for (int i = 0; i < 3; ++i) su[i] = orient3d(t[0], t[1], t[2], u[i]);
    if ((su[0] > 0 && su[1] > 0 && su[2] > 0) || (su[0] < 0 && su[1] < 0 && su[2] < 0)) return false;
    if (!du && su[0] == 0 && su[1] == 0 && su[2] == 0) return triangles_2d(t, u, dominant_axis(nt));
  }
  if (!du) {
    for (int i = 0; i < 3; ++i) st[i] = orient3d(u[0], u[1], u[2], t[i]);
    if ((st[0] > 0 && st[1] > 0 && st[2] > 0) || (st[0] < 0 && st[1] < 0 && st[2] < 0)) return false;
  }
  // Not coplanar (or degenerate): they meet exactly when an edge of one meets the other.
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    if (du ? segment_triangle(t[i], t[j], u) : segment_triangle_sided(t[i], t[j], u, nu, st[i], st[j]))
      return true;
  }
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    if (dt ? segment_triangle(u[i], u[j], t) : segment_triangle_sided(u[i], u[j], t, nt, su[i], su[j]))
      return true;
  }
  return false;
}

/// Whether two closed triangles meet (touching counts). Any vertex order, either argument order.
CANOPY_HD_OUTLINE inline bool triangles_intersect(const Vec3f* pa, const Vec3f* pb) {
  D3 a[3], b[3];
  const D3 *t, *u;
  canonical_pair(pa, pb, a, b, t, u);
  return triangles_intersect_canonical(t, u);
}

/// Whether p lies in the closed convex solid bounded by triangles (outward, counter-clockwise
/// seen from outside): on the inner side of, or on, every face plane, and strictly inside at
/// least one. Degenerate faces do not constrain; a solid of no volume (all faces flat or
/// degenerate, as a zero-length or zero-radius cylinder) contains nothing beyond its surface,
/// which the triangle tests see.
CANOPY_HD inline bool point_in_convex(D3 p, const Vec3f* vertices, const unsigned* indices, int triangles) {
  bool inner = false;
  for (int f = 0; f < triangles; ++f) {
    const D3 a = d3(vertices[indices[3 * f]]), b = d3(vertices[indices[3 * f + 1]]),
             c = d3(vertices[indices[3 * f + 2]]);
    const double o = orient3d(a, b, c, p);
    if (o > 0) return false;
    inner |= o < 0;
  }
  return inner;
}

}  // namespace canopy
