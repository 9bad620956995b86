#pragma once
/// The CPU backend's form of obb_overlap (geometry/obb.hpp) for 8 organ pairs at once: the
/// pairs that pass the organ boxes and the adjacency rule wait in a batch, and the batch's OBB
/// tests run together in lanes of 8 floats (GCC vector extensions), every separating axis
/// computed for every lane and the answers joined at the end. Per lane these are obb_overlap's
/// very operations in its very order (no fused multiply-add: -ffp-contract=off), so the answer
/// is the same bit for bit; only the early exits are gone. Measured on the default 1,000-plant
/// stand (bench/results/README.md, thirty-second session): one OBB test at a time cost about
/// 100 ns, and computing fewer of its terms did not change that: its branches, taken one way or
/// the other as the boxes come, cost more than its arithmetic.
/// tests/collision/test_obb_lanes.cpp holds the two equal lane by lane. Host only: nvcc never
/// reads this file.
#include "collision/organ_rows.hpp"
#include "geometry/obb.hpp"

#include <cstdint>

namespace canopy {

/// Up to 8 OBB pairs (a, b moved by an offset into a's frame) laid out by lane.
struct ObbBatch {
  static constexpr int kLanes = 8;
  /// Per component (x, y, z, then the 3 axes' x, y, z, the 3 half extents and the radius):
  /// 16 floats of a's OBB, 16 of b's, and the offset's 3, each in 8 lanes.
  alignas(32) float a[16][kLanes] = {};
  alignas(32) float b[16][kLanes] = {};
  alignas(32) float offset[3][kLanes] = {};
  std::int32_t organ_a[kLanes] = {}, organ_b[kLanes] = {}, plant_a[kLanes] = {}, plant_b[kLanes] = {};
  int size = 0;

  bool full() const { return size == kLanes; }
  void add(const Obb& oa, const Obb& ob, Vec3f off, std::int32_t ia, std::int32_t ib, std::int32_t pa, std::int32_t pb) {
    put(a, oa);
    put(b, ob);
    offset[0][size] = off.x, offset[1][size] = off.y, offset[2][size] = off.z;
    organ_a[size] = ia, organ_b[size] = ib, plant_a[size] = pa, plant_b[size] = pb;
    ++size;
  }
  /// Bit t set where obb_overlap(a of lane t, b of lane t, offset of lane t) holds (t < size).
  unsigned overlapping() const;

 private:
  void put(float (*to)[kLanes], const Obb& o) {
    const float v[16] = {o.centre.x,  o.centre.y,  o.centre.z,  o.axis[0].x, o.axis[0].y, o.axis[0].z,
                         o.axis[1].x, o.axis[1].y, o.axis[1].z, o.axis[2].x, o.axis[2].y, o.axis[2].z,
                         o.half[0],   o.half[1],   o.half[2],   o.radius};
    for (int k = 0; k < 16; ++k) to[k][size] = v[k];
  }
};

inline unsigned ObbBatch::overlapping() const {
  using namespace lanes_detail;
  const auto abs8 = [](F8 v) {
    I8 bits;
    std::memcpy(&bits, &v, sizeof v);
    bits &= 0x7fffffff;
    std::memcpy(&v, &bits, sizeof v);
    return v;
  };
  // obb_overlap's names: gap (= d) from a's centre to b's moved, reach of the spheres, r and
  // |r| + eps, d along a's axes.
  constexpr float kEps = 1e-6f;
  const F8 gx = (load8(b[0]) + load8(offset[0])) - load8(a[0]);
  const F8 gy = (load8(b[1]) + load8(offset[1])) - load8(a[1]);
  const F8 gz = (load8(b[2]) + load8(offset[2])) - load8(a[2]);
  const F8 reach = load8(a[15]) + load8(b[15]);
  I8 apart = (gx * gx + gy * gy + gz * gz) > reach * reach * (1 + 4 * kBoundRelSlack);
  F8 ax[3][3], bx[3][3], ah[3], bh[3];
  for (int i = 0; i < 3; ++i) {
    for (int c = 0; c < 3; ++c) ax[i][c] = load8(a[3 + 3 * i + c]), bx[i][c] = load8(b[3 + 3 * i + c]);
    ah[i] = load8(a[12 + i]), bh[i] = load8(b[12 + i]);
  }
  F8 r[3][3], ar[3][3], t[3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      r[i][j] = ax[i][0] * bx[j][0] + ax[i][1] * bx[j][1] + ax[i][2] * bx[j][2];
      ar[i][j] = abs8(r[i][j]) + kEps;
    }
  for (int i = 0; i < 3; ++i) t[i] = gx * ax[i][0] + gy * ax[i][1] + gz * ax[i][2];
  for (int i = 0; i < 3; ++i) apart |= abs8(t[i]) > ah[i] + bh[0] * ar[i][0] + bh[1] * ar[i][1] + bh[2] * ar[i][2];
  for (int j = 0; j < 3; ++j)
    apart |= abs8(t[0] * r[0][j] + t[1] * r[1][j] + t[2] * r[2][j]) >
             ah[0] * ar[0][j] + ah[1] * ar[1][j] + ah[2] * ar[2][j] + bh[j];
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const F8 ra = ah[i1] * ar[i2][j] + ah[i2] * ar[i1][j];
      const F8 rb = bh[j1] * ar[i][j2] + bh[j2] * ar[i][j1];
      apart |= abs8(t[i2] * r[i1][j] - t[i1] * r[i2][j]) > ra + rb;
    }
  }
  return ~bits8(apart) & ((1u << size) - 1);
}

}  // namespace canopy
