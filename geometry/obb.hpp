#pragma once
/// Oriented bounding boxes of organs (Ding et al. 2019 §3.2.2: the "simplified OBB", the
/// prototype's local box carried by the organ transform, so building or refitting one is a
/// matrix product) and the separating-axis test (Gottschalk, Lin & Manocha 1996; Ericsson,
/// Real-Time Collision Detection §4.4.1). Shared by the CPU and CUDA backends.
#include "geometry/hd.hpp"
#include "geometry/prototype.hpp"
#include "geometry/vec.hpp"

namespace canopy {

struct Obb {
  Vec3f centre;
  Vec3f axis[3];  // orthonormal
  float half[3];  // half extents along the axes
  float radius;   // of the bounding sphere about the centre: a quick rejection first
};

/// Relative and absolute slack added to every bound so that float rounding never lets a vertex
/// of the organ's mesh (computed with the same transform) fall outside it. Bounds only: exact
/// answers never use it.
inline constexpr float kBoundRelSlack = 4e-6f;
inline constexpr float kBoundAbsSlack = 1e-7f;

/// Sets the bounding-sphere radius from the half extents (after any change to them).
CANOPY_HD inline void set_radius(Obb& o) {
  o.radius =
      sqrtf(o.half[0] * o.half[0] + o.half[1] * o.half[1] + o.half[2] * o.half[2]) * (1 + kBoundRelSlack);
}

CANOPY_HD inline Vec3f unit_or_zero(Vec3f v, float& len) {
  len = sqrtf(dot(v, v));
  return len > 0 ? v * (1.0f / len) : Vec3f{0, 0, 0};
}

/// The organ's OBB: `local` (the prototype's box) carried by `m`, grown by `inflate` (a
/// clearance) plus the rounding slack. Zero columns (zero-length or zero-width organs) get an
/// axis completing the frame and a zero extent.
CANOPY_HD inline Obb make_obb(const Affine3f& m, const Box3f& local, float inflate) {
  Obb o;
  const Vec3f c{0.5f * (local.lo.x + local.hi.x), 0.5f * (local.lo.y + local.hi.y),
                0.5f * (local.lo.z + local.hi.z)};
  const float h[3] = {0.5f * (local.hi.x - local.lo.x), 0.5f * (local.hi.y - local.lo.y),
                      0.5f * (local.hi.z - local.lo.z)};
  o.centre = apply(m, c);
  const Vec3f col[3] = {m.c0, m.c1, m.c2};
  float len[3];
  for (int k = 0; k < 3; ++k) o.axis[k] = unit_or_zero(col[k], len[k]);
  for (int k = 0; k < 3; ++k) {
    if (len[k] > 0) continue;
    const Vec3f a = o.axis[(k + 1) % 3], b = o.axis[(k + 2) % 3];
    Vec3f v = cross(a, b);
    float l = 0;
    v = unit_or_zero(v, l);
    if (l == 0) {  // two columns missing: any frame around the one left
      const Vec3f known = dot(a, a) > 0 ? a : dot(b, b) > 0 ? b : Vec3f{1, 0, 0};
      const Vec3f helper = fabsf(known.z) < 0.9f ? Vec3f{0, 0, 1} : Vec3f{1, 0, 0};
      v = unit_or_zero(cross(known, helper), l);
    }
    o.axis[k] = v;
  }
  float size = fabsf(o.centre.x) + fabsf(o.centre.y) + fabsf(o.centre.z);
  for (int k = 0; k < 3; ++k) size += h[k] * len[k];
  for (int k = 0; k < 3; ++k) o.half[k] = h[k] * len[k] + inflate + kBoundRelSlack * size + kBoundAbsSlack;
  set_radius(o);
  return o;
}

/// The OBB grown by `by` on every side; its radius grows by at most by x sqrt(3) (rounded up).
CANOPY_HD inline Obb grown(Obb o, float by) {
  for (int k = 0; k < 3; ++k) o.half[k] += by;
  o.radius += 1.7320509f * by * (1 + 4 * kBoundRelSlack);
  return o;
}

/// The axis-aligned box around an OBB (its centre plus or minus the axes' reach along x, y and
/// z), grown by the bounds' rounding slack so that it holds every point the OBB holds: the
/// organ-pair stage's pre-test (collision/organ_blocks.hpp). A NaN box meets nothing.
CANOPY_HD inline Box3f obb_aabb(const Obb& o) {
  const float ex =
      fabsf(o.axis[0].x) * o.half[0] + fabsf(o.axis[1].x) * o.half[1] + fabsf(o.axis[2].x) * o.half[2];
  const float ey =
      fabsf(o.axis[0].y) * o.half[0] + fabsf(o.axis[1].y) * o.half[1] + fabsf(o.axis[2].y) * o.half[2];
  const float ez =
      fabsf(o.axis[0].z) * o.half[0] + fabsf(o.axis[1].z) * o.half[1] + fabsf(o.axis[2].z) * o.half[2];
  const float size = fabsf(o.centre.x) + fabsf(o.centre.y) + fabsf(o.centre.z) + ex + ey + ez;
  const float s = kBoundRelSlack * size + kBoundAbsSlack;
  return Box3f{{o.centre.x - ex - s, o.centre.y - ey - s, o.centre.z - ez - s},
               {o.centre.x + ex + s, o.centre.y + ey + s, o.centre.z + ez + s}};
}

/// Corner i (0-7) of an OBB: bit k of i picks the + side of axis k.
CANOPY_HD inline Vec3f obb_corner(const Obb& o, int i) {
  const float sx = (i & 1) ? o.half[0] : -o.half[0], sy = (i & 2) ? o.half[1] : -o.half[1],
              sz = (i & 4) ? o.half[2] : -o.half[2];
  return o.centre + o.axis[0] * sx + o.axis[1] * sy + o.axis[2] * sz;
}

/// The 8 corners of an OBB.
CANOPY_HD inline void obb_corners(const Obb& o, Vec3f out[8]) {
  for (int i = 0; i < 8; ++i) out[i] = obb_corner(o, i);
}

/// Whether two OBBs overlap (closed boxes), with b shifted by `offset`. The 15 axes of the
/// separating-axis test; an epsilon in |R| keeps near-parallel edge pairs (whose cross-product
/// axes vanish) from reporting a false separation (Ericsson §4.4.1). Conservative: never
/// reports separated boxes as separated unless they are.
CANOPY_HD inline bool obb_overlap(const Obb& a, const Obb& b, Vec3f offset) {
  constexpr float kEps = 1e-6f;
  const Vec3f gap = b.centre + offset - a.centre;
  const float reach = a.radius + b.radius;
  if (dot(gap, gap) > reach * reach * (1 + 4 * kBoundRelSlack)) return false;  // bounding spheres apart
  float r[3][3], ar[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      r[i][j] = dot(a.axis[i], b.axis[j]);
      ar[i][j] = fabsf(r[i][j]) + kEps;
    }
  const Vec3f d = b.centre + offset - a.centre;
  const float t[3] = {dot(d, a.axis[0]), dot(d, a.axis[1]), dot(d, a.axis[2])};
  for (int i = 0; i < 3; ++i)
    if (fabsf(t[i]) > a.half[i] + b.half[0] * ar[i][0] + b.half[1] * ar[i][1] + b.half[2] * ar[i][2])
      return false;
  for (int j = 0; j < 3; ++j)
    if (fabsf(t[0] * r[0][j] + t[1] * r[1][j] + t[2] * r[2][j]) >
        a.half[0] * ar[0][j] + a.half[1] * ar[1][j] + a.half[2] * ar[2][j] + b.half[j])
      return false;
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const float ra = a.half[i1] * ar[i2][j] + a.half[i2] * ar[i1][j];
      const float rb = b.half[j1] * ar[i][j2] + b.half[j2] * ar[i][j1];
      if (fabsf(t[i2] * r[i1][j] - t[i1] * r[i2][j]) > ra + rb) return false;
    }
  }
  return true;
}

}  // namespace canopy
