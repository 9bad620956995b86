#pragma once
/// Leaf collision detection boxes (Song 2013, as used by Ding et al. 2019 §3.2.2): an OBB with
/// one axis fixed to the vertical, so two of them are separated on one of 5 axes (the vertical
/// and the two horizontal axes of each) instead of 15. Shared by the CPU and CUDA backends.
#include "geometry/hd.hpp"
#include "geometry/obb.hpp"
#include "geometry/vec.hpp"

#include <cmath>

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

/// An LCD box in the form its overlap test reads: the centre of its horizontal rectangle in the
/// plant frame (cx, cy), its axis, its half sizes along u and v, and its vertical range; made
/// once per box (lcd_centred) rather than at every test, where the pass tests each cluster's
/// root against a dozen others. Half a cache line. An empty box's form has an empty vertical range (+inf,
/// -inf), which meets no box of finite height.
struct LcdCentred {
  float cx = 0, cy = 0, ax = 1, ay = 0, hu = 0, hv = 0;
  float z_lo = 0, z_hi = -1;
};

CANOPY_HD inline LcdCentred lcd_centred(const Lcd& l) {
  if (lcd_empty(l)) return LcdCentred{0, 0, 1, 0, 0, 0, INFINITY, -INFINITY};
  // Centre (u, v in the box's own frame) and half sizes; then the centre in the plant frame.
  const float cu = 0.5f * (l.lo[0] + l.hi[0]), cv = 0.5f * (l.lo[1] + l.hi[1]);
  const float hu = 0.5f * (l.hi[0] - l.lo[0]), hv = 0.5f * (l.hi[1] - l.lo[1]);
  return LcdCentred{l.ax * cu - l.ay * cv, l.ay * cu + l.ax * cv, l.ax, l.ay, hu, hv, l.lo[2], l.hi[2]};
}

/// Whether two LCD boxes overlap (closed), with b moved by `offset`: the vertical axis, then the
/// two horizontal axes of each box, as the separating-axis test of two rectangles in the plane
/// (Gottschalk, Lin & Manocha 1996; Ericson, Real-Time Collision Detection §4.4.1, in 2D). The
/// four axes share the cosine and sine of the angle between the boxes, instead of both boxes
/// being projected anew on every axis.
CANOPY_HD inline bool lcd_overlap(const LcdCentred& a, const LcdCentred& b, Vec3f offset) {
  if (a.z_lo > b.z_hi + offset.z || b.z_lo + offset.z > a.z_hi) return false;
  // From a's centre to b's, in the plant frame.
  const float dx = (b.cx + offset.x) - a.cx;
  const float dy = (b.cy + offset.y) - a.cy;
  // |cos| and |sin| of the angle between the boxes' u axes: what each axis of one box makes
  // with both axes of the other.
  const float c = fabsf(a.ax * b.ax + a.ay * b.ay), sn = fabsf(a.ax * b.ay - a.ay * b.ax);
  if (fabsf(dx * a.ax + dy * a.ay) > a.hu + (b.hu * c + b.hv * sn)) return false;  // a's u axis
  if (fabsf(dy * a.ax - dx * a.ay) > a.hv + (b.hu * sn + b.hv * c)) return false;  // a's v axis
  if (fabsf(dx * b.ax + dy * b.ay) > b.hu + (a.hu * c + a.hv * sn)) return false;  // b's u axis
  if (fabsf(dy * b.ax - dx * b.ay) > b.hv + (a.hu * sn + a.hv * c)) return false;  // b's v axis
  return true;
}

/// The same test on two boxes as they are kept: none overlaps an empty box.
CANOPY_HD inline bool lcd_overlap(const Lcd& a, const Lcd& b, Vec3f offset) {
  if (lcd_empty(a) || lcd_empty(b)) return false;
  return lcd_overlap(lcd_centred(a), lcd_centred(b), offset);
}

}  // namespace canopy
