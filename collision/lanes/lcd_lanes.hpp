#pragma once
/// The CPU backend's form of lcd_overlap (geometry/lcd.hpp) for one cluster's root against 8 of
/// the other plant's at once (collision/lanes/organ_rows.hpp lane_clusters_overlapping), in lanes of 8
/// floats (GCC vector extensions): every axis computed for every lane and the answers joined at
/// the end, rather than one test and one branch on its answer per cluster pair (between plants
/// about 60 % of them pass, so the branch goes either way). Per lane these are lcd_overlap's
/// very operations in its very order (no fused multiply-add: -ffp-contract=off), so the answer
/// is the same bit for bit; tests/collision/lanes/test_lcd_lanes.cpp holds the two equal lane by lane.
/// Host only: nvcc never reads this file.
#include "collision/lanes/lanes8.hpp"
#include "geometry/lcd.hpp"

#include <cstdint>

namespace canopy {

static_assert(sizeof(LcdCentred) == 8 * sizeof(float), "an LCD box's centred form is read as 8 floats");

/// Bit t set where lcd_overlap(a, b_t, offset) holds, lb[k] holding field k of the 8 boxes b_t
/// (LcdCentred's fields in order: cx, cy, ax, ay, hu, hv, z_lo, z_hi).
inline unsigned lcd_overlapping8(const LcdCentred& a, const lanes_detail::F8* lb, Vec3f offset) {
  using namespace lanes_detail;
  I8 apart = (a.z_lo > lb[7] + offset.z) | (lb[6] + offset.z > a.z_hi);
  const F8 dx = (lb[0] + offset.x) - a.cx;
  const F8 dy = (lb[1] + offset.y) - a.cy;
  const F8 c = abs8(a.ax * lb[2] + a.ay * lb[3]), sn = abs8(a.ax * lb[3] - a.ay * lb[2]);
  apart |= abs8(dx * a.ax + dy * a.ay) > a.hu + (lb[4] * c + lb[5] * sn);
  apart |= abs8(dy * a.ax - dx * a.ay) > a.hv + (lb[4] * sn + lb[5] * c);
  apart |= abs8(dx * lb[2] + dy * lb[3]) > lb[4] + (a.hu * c + a.hv * sn);
  apart |= abs8(dy * lb[2] - dx * lb[3]) > lb[5] + (a.hu * sn + a.hv * c);
  return ~bits8(apart) & 0xffu;
}

/// Bit t set where lcd_overlap(a, b_t, offset) holds, the 8 boxes b_t a group of LCD lanes
/// (collision/lanes/organ_lanes.hpp LcdLanes: field k of the 8 at group + 8 k).
inline unsigned lcd_overlapping8(const LcdCentred& a, const float* group, Vec3f offset) {
  using namespace lanes_detail;
  F8 lb[8];
  for (int k = 0; k < 8; ++k) lb[k] = load8(group + 8 * k);
  return lcd_overlapping8(a, lb, offset);
}

}  // namespace canopy
