#pragma once
/// Rotations and rigid motions in double, shared by both backends (CANOPY_HD): the turn search
/// of resolution makes a turn's motion and the poses and boxes it carries the same way on the
/// host and on the device, so both find the same turns.
#include "geometry/hd.hpp"
#include "geometry/obb.hpp"
#include "geometry/vec.hpp"

namespace canopy {

/// Row-major 3x3 rotation in double.
struct Mat3d {
  double m[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
};
// The small products are inline: the turn search makes millions of them.
CANOPY_HD inline Mat3d operator*(const Mat3d& a, const Mat3d& b) {
  Mat3d c;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      c.m[3 * i + j] = a.m[3 * i] * b.m[j] + a.m[3 * i + 1] * b.m[3 + j] + a.m[3 * i + 2] * b.m[6 + j];
  return c;
}
CANOPY_HD inline Vec3d operator*(const Mat3d& a, Vec3d v) {
  return {a.m[0] * v.x + a.m[1] * v.y + a.m[2] * v.z, a.m[3] * v.x + a.m[4] * v.y + a.m[5] * v.z,
          a.m[6] * v.x + a.m[7] * v.y + a.m[8] * v.z};
}
CANOPY_HD inline Mat3d transpose(const Mat3d& a) {
  Mat3d t;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) t.m[3 * i + j] = a.m[3 * j + i];
  return t;
}
/// Rodrigues' formula with the angle's cosine c and sine s given (many axes turned by one
/// angle; the host computes them, so both backends use the same values): rotation about the
/// unit axis k.
CANOPY_HD inline Mat3d axis_angle(Vec3d k, double c, double s) {
  const double v = 1 - c;
  Mat3d r;
  r.m[0] = c + k.x * k.x * v, r.m[1] = k.x * k.y * v - k.z * s, r.m[2] = k.x * k.z * v + k.y * s;
  r.m[3] = k.y * k.x * v + k.z * s, r.m[4] = c + k.y * k.y * v, r.m[5] = k.y * k.z * v - k.x * s;
  r.m[6] = k.z * k.x * v - k.y * s, r.m[7] = k.z * k.y * v + k.x * s, r.m[8] = c + k.z * k.z * v;
  return r;
}

/// A rigid motion x -> r x + t.
struct Motion {
  Mat3d r;
  Vec3d t;
};
CANOPY_HD inline Motion compose(const Motion& a, const Motion& b) {
  return {a.r * b.r, a.r * b.t + a.t};
}  // a o b
CANOPY_HD inline Motion rotation_about(Vec3d p, const Mat3d& r) { return {r, p - r * p}; }
CANOPY_HD inline Vec3d apply(const Motion& m, Vec3d p) { return m.r * p + m.t; }
/// The motion applied to an organ transform (columns rotated, joint moved), rounded to float.
CANOPY_HD inline Affine3f apply(const Motion& m, const Affine3f& a) {
  Affine3f o;
  o.c0 = to_float(m.r * to_double(a.c0));
  o.c1 = to_float(m.r * to_double(a.c1));
  o.c2 = to_float(m.r * to_double(a.c2));
  o.t = to_float(apply(m, to_double(a.t)));
  return o;
}
/// The OBB `o` carried by the rigid motion `m` and grown by `inflate`; the rounding slack of the
/// original box covers the float rounding of the carried one.
CANOPY_HD inline Obb carried_box(const Obb& o, const Motion& m, float inflate) {
  Obb r;
  r.centre = to_float(apply(m, to_double(o.centre)));
  for (int k = 0; k < 3; ++k)
    r.axis[k] = to_float(m.r * to_double(o.axis[k])), r.half[k] = o.half[k] + inflate;
  set_radius(r);
  return r;
}

}  // namespace canopy
