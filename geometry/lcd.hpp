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

/// The interval of box `l` projected on the horizontal unit direction (dx, dy), with the box's
/// frame moved by `offset`.
CANOPY_HD inline void lcd_project(const Lcd& l, float dx, float dy, Vec3f offset, float& lo, float& hi) {
  // Box centre and half sizes in its own (a, b) frame.
  const float cu = 0.5f * (l.lo[0] + l.hi[0]), cv = 0.5f * (l.lo[1] + l.hi[1]);
  const float hu = 0.5f * (l.hi[0] - l.lo[0]), hv = 0.5f * (l.hi[1] - l.lo[1]);
  const float cx = l.ax * cu - l.ay * cv + offset.x, cy = l.ay * cu + l.ax * cv + offset.y;
  const float c = cx * dx + cy * dy;
  const float r = hu * fabsf(l.ax * dx + l.ay * dy) + hv * fabsf(-l.ay * dx + l.ax * dy);
  lo = c - r;
  hi = c + r;
}

/// Whether two LCD boxes overlap (closed), with b moved by `offset`: the vertical axis, then the
/// two horizontal axes of each box.
CANOPY_HD inline bool lcd_overlap(const Lcd& a, const Lcd& b, Vec3f offset) {
  if (lcd_empty(a) || lcd_empty(b)) return false;
  if (a.lo[2] > b.hi[2] + offset.z || b.lo[2] + offset.z > a.hi[2]) return false;
  const float axes[4][2] = {{a.ax, a.ay}, {-a.ay, a.ax}, {b.ax, b.ay}, {-b.ay, b.ax}};
  for (int k = 0; k < 4; ++k) {
    float alo, ahi, blo, bhi;
    lcd_project(a, axes[k][0], axes[k][1], {0, 0, 0}, alo, ahi);
    lcd_project(b, axes[k][0], axes[k][1], offset, blo, bhi);
    if (alo > bhi || blo > ahi) return false;
  }
  return true;
}

}  // namespace canopy
