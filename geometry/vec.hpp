#pragma once
/// Plain vector and affine types shared by the host and CUDA backends (CANOPY_HD).
#include "geometry/hd.hpp"

#include <cmath>

namespace canopy {

/// min and max that compile to single instructions (fminf/fmaxf must honour NaN and become
/// library calls); arguments here are never NaN.
CANOPY_HD inline float min_f(float a, float b) { return a < b ? a : b; }
CANOPY_HD inline float max_f(float a, float b) { return a > b ? a : b; }

struct Vec3f {
  float x = 0, y = 0, z = 0;
};

CANOPY_HD inline Vec3f operator+(Vec3f a, Vec3f b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
CANOPY_HD inline Vec3f operator-(Vec3f a, Vec3f b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
CANOPY_HD inline Vec3f operator*(Vec3f a, float s) { return {a.x * s, a.y * s, a.z * s}; }
CANOPY_HD inline Vec3f operator*(float s, Vec3f a) { return {a.x * s, a.y * s, a.z * s}; }
CANOPY_HD inline Vec3f operator-(Vec3f a) { return {-a.x, -a.y, -a.z}; }
CANOPY_HD inline float dot(Vec3f a, Vec3f b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
CANOPY_HD inline Vec3f cross(Vec3f a, Vec3f b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
CANOPY_HD inline float length(Vec3f a) { return sqrtf(dot(a, a)); }

/// A 3x4 affine map x -> A x + t stored as four columns; for an organ the columns are its
/// heading H, width direction L and normal U, each scaled by the prototype's size, and its joint.
struct Affine3f {
  Vec3f c0, c1, c2, t;
};

CANOPY_HD inline Vec3f apply(const Affine3f& m, Vec3f p) {
  return m.c0 * p.x + m.c1 * p.y + m.c2 * p.z + m.t;
}
CANOPY_HD inline Vec3f apply_linear(const Affine3f& m, Vec3f p) {
  return m.c0 * p.x + m.c1 * p.y + m.c2 * p.z;
}

/// Double-precision vector: turtle state, plant origins, exports, and the turns of resolution
/// (whose rigid motions both backends make, geometry/motion.hpp).
struct Vec3d {
  double x = 0, y = 0, z = 0;
};
CANOPY_HD inline Vec3d operator+(Vec3d a, Vec3d b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
CANOPY_HD inline Vec3d operator-(Vec3d a, Vec3d b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
CANOPY_HD inline Vec3d operator*(Vec3d a, double s) { return {a.x * s, a.y * s, a.z * s}; }
CANOPY_HD inline Vec3d operator*(double s, Vec3d a) { return {a.x * s, a.y * s, a.z * s}; }
CANOPY_HD inline double dot(Vec3d a, Vec3d b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
CANOPY_HD inline Vec3d cross(Vec3d a, Vec3d b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(Vec3d a) { return std::sqrt(dot(a, a)); }
inline Vec3d normalized(Vec3d a) {
  const double n = length(a);
  return n > 0 ? a * (1 / n) : a;
}
CANOPY_HD inline Vec3f to_float(Vec3d a) {
  return {static_cast<float>(a.x), static_cast<float>(a.y), static_cast<float>(a.z)};
}
CANOPY_HD inline Vec3d to_double(Vec3f a) { return {a.x, a.y, a.z}; }

}  // namespace canopy
