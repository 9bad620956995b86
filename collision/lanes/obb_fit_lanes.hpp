#pragma once
/// The CPU backend's form of make_obb (geometry/obb.hpp) for 8 organs at once, for the tree's
/// build and refit: per lane make_obb's very operations in its very order (no fused
/// multiply-add: -ffp-contract=off; sqrtf and the division are correctly rounded in lanes too),
/// so each OBB is the scalar one bit for bit, as the CUDA backend, which fits with make_obb
/// itself, must see it (tests/collision/lanes/test_obb_fit_lanes.cpp). A lane with a column of zero or
/// undefined length (make_obb's completion of the frame) is made by make_obb itself. make_obb
/// one organ at a time is a large share of the build (bench_detect: about a quarter). Host only:
/// nvcc never reads this file.
#include "collision/lanes/lanes8.hpp"
#include "geometry/obb.hpp"

#include <cstring>

namespace canopy {

/// out[t] = make_obb(*transform[t], *local[t], inflate) for t < count (count 1 to 8).
inline void make_obbs8(const Affine3f* const* transform, const Box3f* const* local, int count, float inflate,
                       Obb* const* out) {
  using namespace lanes_detail;
  static_assert(sizeof(Affine3f) == 12 * sizeof(float) && sizeof(Box3f) == 6 * sizeof(float));
  const auto abs8 = [](F8 v) {  // fabsf lane by lane: the sign bit cleared
    I8 bits;
    std::memcpy(&bits, &v, sizeof v);
    bits &= 0x7fffffff;
    std::memcpy(&v, &bits, sizeof v);
    return v;
  };
  // m[k]: float k of the transforms (columns c0 c1 c2, then t), b[k]: of the local boxes (lo, hi).
  F8 m[12], b[6];
  for (int t = 0; t < 8; ++t) {
    const int from = t < count ? t : 0;
    float f[12], g[6];
    std::memcpy(f, transform[from], sizeof f);
    std::memcpy(g, local[from], sizeof g);
    for (int k = 0; k < 12; ++k) m[k][t] = f[k];
    for (int k = 0; k < 6; ++k) b[k][t] = g[k];
  }
  const F8 c[3] = {0.5f * (b[0] + b[3]), 0.5f * (b[1] + b[4]), 0.5f * (b[2] + b[5])};
  const F8 h[3] = {0.5f * (b[3] - b[0]), 0.5f * (b[4] - b[1]), 0.5f * (b[5] - b[2])};
  // apply(m, c): c0 * c.x + c1 * c.y + c2 * c.z + t, coordinate by coordinate.
  F8 centre[3];
  for (int k = 0; k < 3; ++k) centre[k] = m[k] * c[0] + m[3 + k] * c[1] + m[6 + k] * c[2] + m[9 + k];
  // unit_or_zero of each column.
  F8 axis[3][3], len[3];
  I8 odd = {0, 0, 0, 0, 0, 0, 0, 0};
  for (int j = 0; j < 3; ++j) {
    const F8 x = m[3 * j], y = m[3 * j + 1], z = m[3 * j + 2];
    len[j] = sqrt8(x * x + y * y + z * z);
    odd |= ~(len[j] > 0);
    const F8 inv = 1.0f / len[j];
    axis[j][0] = x * inv, axis[j][1] = y * inv, axis[j][2] = z * inv;
  }
  F8 size = abs8(centre[0]) + abs8(centre[1]) + abs8(centre[2]);
  for (int k = 0; k < 3; ++k) size += h[k] * len[k];
  F8 half[3];
  for (int k = 0; k < 3; ++k) half[k] = h[k] * len[k] + inflate + kBoundRelSlack * size + kBoundAbsSlack;
  const F8 radius = sqrt8(half[0] * half[0] + half[1] * half[1] + half[2] * half[2]) * (1 + kBoundRelSlack);
  const unsigned scalar = bits8(odd);
  for (int t = 0; t < count; ++t) {
    if ((scalar >> t) & 1u) {
      *out[t] = make_obb(*transform[t], *local[t], inflate);
      continue;
    }
    Obb& o = *out[t];
    o.centre = {centre[0][t], centre[1][t], centre[2][t]};
    for (int j = 0; j < 3; ++j) o.axis[j] = {axis[j][0][t], axis[j][1][t], axis[j][2][t]};
    for (int k = 0; k < 3; ++k) o.half[k] = half[k][t];
    o.radius = radius[t];
  }
}

}  // namespace canopy
