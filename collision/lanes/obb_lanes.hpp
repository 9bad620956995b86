#pragma once
/// The CPU backend's form of obb_overlap (geometry/obb.hpp) for 8 organ pairs at once: the
/// pairs that pass the organ boxes and the adjacency rule wait in a batch, and the batch's OBB
/// tests run together in lanes of 8 floats (GCC vector extensions), every separating axis
/// computed for every lane and the answers joined at the end. Per lane these are obb_overlap's
/// very operations in its very order (no fused multiply-add: -ffp-contract=off), so the answer
/// is the same bit for bit; only the early exits are gone. One OBB test at a time is slow
/// (bench_detect: about 100 ns each), and computing fewer of its terms does not change that: its
/// branches, taken one way or the other as the boxes come, cost more than its arithmetic.
/// tests/collision/lanes/test_obb_lanes.cpp holds the two equal lane by lane. Host only: nvcc never
/// reads this file.
#include "collision/lanes/lanes8.hpp"
#include "geometry/obb.hpp"

#include <cstdint>
#include <cstring>

namespace canopy {

/// Up to 8 OBB pairs (a, b moved by an offset into a's frame), kept as pointers to the tree's
/// OBBs until the test: it loads the 8 OBBs of each side together, 64 bytes each, and turns them
/// into lanes by component (an 8 x 8 transpose of registers), rather than copying every pair's
/// 32 floats one by one into lanes as the pair comes (which waits on each OBB's load in turn).
/// The OBBs must stay where they are until overlapping().
struct ObbBatch {
  static constexpr int kLanes = 8;
  const Obb* a[kLanes] = {};
  const Obb* b[kLanes] = {};
  alignas(32) float offset[3][kLanes] = {};
  std::int32_t organ_a[kLanes] = {}, organ_b[kLanes] = {}, plant_a[kLanes] = {}, plant_b[kLanes] = {};
  int size = 0;

  bool full() const { return size == kLanes; }
  void add(const Obb& oa, const Obb& ob, Vec3f off, std::int32_t ia, std::int32_t ib, std::int32_t pa,
           std::int32_t pb) {
    a[size] = &oa, b[size] = &ob;
    __builtin_prefetch(&oa), __builtin_prefetch(&ob);
    offset[0][size] = off.x, offset[1][size] = off.y, offset[2][size] = off.z;
    organ_a[size] = ia, organ_b[size] = ib, plant_a[size] = pa, plant_b[size] = pb;
    ++size;
  }
  /// Bit t set where obb_overlap(a of lane t, b of lane t, offset of lane t) holds (t < size);
  /// an empty batch reads no OBB.
  unsigned overlapping() const;
};

namespace lanes_detail {
static_assert(sizeof(Obb) == 16 * sizeof(float),
              "an OBB is read as 16 floats: centre, 3 axes, half extents, radius");

/// out[k] lane t: float k of OBB obbs[t] (centre x y z, the axes' x y z, half extents, radius,
/// in Obb's order); lanes from `size` on repeat lane 0's OBB.
inline void obb_components(const Obb* const* obbs, int size, F8 (&out)[16]) {
  for (int half = 0; half < 2; ++half) {
    const float* rows[8];
    for (int t = 0; t < 8; ++t) rows[t] = reinterpret_cast<const float*>(obbs[t < size ? t : 0]) + 8 * half;
    transpose8(rows, &out[8 * half]);
  }
}
}  // namespace lanes_detail

inline unsigned ObbBatch::overlapping() const {
  using namespace lanes_detail;
  // obb_overlap's names: gap (= d) from a's centre to b's moved, reach of the spheres, r and
  // |r| + eps, d along a's axes.
  constexpr float kEps = 1e-6f;
  if (size == 0) return 0;
  F8 oa[16], ob[16];
  obb_components(a, size, oa);
  obb_components(b, size, ob);
  const F8 gx = (ob[0] + load8(offset[0])) - oa[0];
  const F8 gy = (ob[1] + load8(offset[1])) - oa[1];
  const F8 gz = (ob[2] + load8(offset[2])) - oa[2];
  const F8 reach = oa[15] + ob[15];
  I8 apart = (gx * gx + gy * gy + gz * gz) > reach * reach * (1 + 4 * kBoundRelSlack);
  F8 ax[3][3], bx[3][3], ah[3], bh[3];
  for (int i = 0; i < 3; ++i) {
    for (int c = 0; c < 3; ++c) ax[i][c] = oa[3 + 3 * i + c], bx[i][c] = ob[3 + 3 * i + c];
    ah[i] = oa[12 + i], bh[i] = ob[12 + i];
  }
  F8 r[3][3], ar[3][3], t[3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      r[i][j] = ax[i][0] * bx[j][0] + ax[i][1] * bx[j][1] + ax[i][2] * bx[j][2];
      ar[i][j] = abs8(r[i][j]) + kEps;
    }
  for (int i = 0; i < 3; ++i) t[i] = gx * ax[i][0] + gy * ax[i][1] + gz * ax[i][2];
  for (int i = 0; i < 3; ++i)
    apart |= abs8(t[i]) > ah[i] + bh[0] * ar[i][0] + bh[1] * ar[i][1] + bh[2] * ar[i][2];
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
