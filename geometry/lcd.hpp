#pragma once
/// Leaf collision detection boxes (Song 2013, as used by Ding et al. 2019 §3.2.2): an OBB with
/// one axis fixed to the vertical, so two of them are separated on one of 5 axes (the vertical
/// and the two horizontal axes of each) instead of 15. Shared by the CPU and CUDA backends.
#include "geometry/hd.hpp"
#include "geometry/obb.hpp"
#include "geometry/vec.hpp"

namespace canopy {

/// Horizontal axis a = (ax, ay) (unit), b = (-ay, ax); the box spans [lo, hi] along a, b and z.
struct Lcd {
  float ax = 1, ay = 0;
  float lo[3] = {0, 0, 0};
  float hi[3] = {-1, -1, -1};  // empty until something is added
};

CANOPY_HD inline bool lcd_empty(const Lcd& l) { return l.lo[0] > l.hi[0]; }

/// Horizontal corner i (0-3) of box `l`, in its plant's frame.
CANOPY_HD inline void lcd_corner(const Lcd& l, int i, float& x, float& y) {
  const float u = (i & 1) ? l.hi[0] : l.lo[0], v = (i & 2) ? l.hi[1] : l.lo[1];
  x = l.ax * u - l.ay * v, y = l.ay * u + l.ax * v;
}

/// Grows `l` (in its own frame) to contain point p.
CANOPY_HD inline void lcd_add(Lcd& l, Vec3f p) {
  const float u = l.ax * p.x + l.ay * p.y, v = -l.ay * p.x + l.ax * p.y;
  const float q[3] = {u, v, p.z};
  if (lcd_empty(l)) {
    for (int k = 0; k < 3; ++k) l.lo[k] = l.hi[k] = q[k];
    return;
  }
  for (int k = 0; k < 3; ++k) {
    l.lo[k] = min_f(l.lo[k], q[k]);
    l.hi[k] = max_f(l.hi[k], q[k]);
  }
}

/// Grows `l` to contain an OBB (its 8 corners). The corners and their projections are made side
/// by side, then taken in corner order as lcd_add of each corner would take them: the same bits
/// (min and max of signed zeros depend on the order).
CANOPY_HD inline void lcd_add(Lcd& l, const Obb& o) {
  float q[3][8];
  for (int i = 0; i < 8; ++i) {
    const Vec3f p = obb_corner(o, i);
    q[0][i] = l.ax * p.x + l.ay * p.y;
    q[1][i] = -l.ay * p.x + l.ax * p.y;
    q[2][i] = p.z;
  }
  int first = 0;
  if (lcd_empty(l)) {
    for (int k = 0; k < 3; ++k) l.lo[k] = l.hi[k] = q[k][0];
    first = 1;
  }
  for (int k = 0; k < 3; ++k)
    for (int i = first; i < 8; ++i) l.lo[k] = min_f(l.lo[k], q[k][i]), l.hi[k] = max_f(l.hi[k], q[k][i]);
}

/// Grows `l` to contain another box of the same orientation.
CANOPY_HD inline void lcd_merge(Lcd& l, const Lcd& o) {
  if (lcd_empty(o)) return;
  if (lcd_empty(l)) {
    l = o;
    return;
  }
  for (int k = 0; k < 3; ++k) {
    l.lo[k] = min_f(l.lo[k], o.lo[k]);
    l.hi[k] = max_f(l.hi[k], o.hi[k]);
  }
}

/// Widens `l` by `by` on every side, plus the rounding slack of its size.
CANOPY_HD inline void lcd_inflate(Lcd& l, float by) {
  float size = 0;
  for (int k = 0; k < 3; ++k) size += fabsf(l.lo[k]) + fabsf(l.hi[k]);
  const float s = by + kBoundRelSlack * size + kBoundAbsSlack;
  for (int k = 0; k < 3; ++k) {
    l.lo[k] -= s;
    l.hi[k] += s;
  }
}

/// Whether two LCD boxes overlap (closed), with b moved by `offset`: the vertical axis, then the
/// two horizontal axes of each box, as the separating-axis test of two rectangles in the plane
/// (Gottschalk, Lin & Manocha 1996; Ericson, Real-Time Collision Detection §4.4.1, in 2D). Each
/// box's centre and half sizes are found once and the four axes share the cosine and sine of
/// the angle between the boxes, instead of both boxes being projected anew on every axis.
CANOPY_HD inline bool lcd_overlap(const Lcd& a, const Lcd& b, Vec3f offset) {
  if (lcd_empty(a) || lcd_empty(b)) return false;
  if (a.lo[2] > b.hi[2] + offset.z || b.lo[2] + offset.z > a.hi[2]) return false;
  // Centres (u, v in each box's own frame) and half sizes.
  const float acu = 0.5f * (a.lo[0] + a.hi[0]), acv = 0.5f * (a.lo[1] + a.hi[1]);
  const float ahu = 0.5f * (a.hi[0] - a.lo[0]), ahv = 0.5f * (a.hi[1] - a.lo[1]);
  const float bcu = 0.5f * (b.lo[0] + b.hi[0]), bcv = 0.5f * (b.lo[1] + b.hi[1]);
  const float bhu = 0.5f * (b.hi[0] - b.lo[0]), bhv = 0.5f * (b.hi[1] - b.lo[1]);
  // From a's centre to b's, in the plant frame.
  const float dx = (b.ax * bcu - b.ay * bcv + offset.x) - (a.ax * acu - a.ay * acv);
  const float dy = (b.ay * bcu + b.ax * bcv + offset.y) - (a.ay * acu + a.ax * acv);
  // |cos| and |sin| of the angle between the boxes' u axes: what each axis of one box makes
  // with both axes of the other.
  const float c = fabsf(a.ax * b.ax + a.ay * b.ay), sn = fabsf(a.ax * b.ay - a.ay * b.ax);
  if (fabsf(dx * a.ax + dy * a.ay) > ahu + (bhu * c + bhv * sn)) return false;   // a's u axis
  if (fabsf(dy * a.ax - dx * a.ay) > ahv + (bhu * sn + bhv * c)) return false;   // a's v axis
  if (fabsf(dx * b.ax + dy * b.ay) > bhu + (ahu * c + ahv * sn)) return false;   // b's u axis
  if (fabsf(dy * b.ax - dx * b.ay) > bhv + (ahu * sn + ahv * c)) return false;   // b's v axis
  return true;
}

}  // namespace canopy
