#pragma once
/// Axis-aligned boxes kept in lanes of 8 floats (structure of arrays), so that the CPU backend
/// tests 8 box pairs at once (collision/lanes/organ_rows.hpp): every cluster's organs' boxes
/// (obb_aabb), and every plant's clusters' boxes (Cluster::box). Part of the MBVT on the host:
/// fit with the OBBs (fit_mbvt) and refit with them (refit_mbvt), a box per organ and cluster.
#include "geometry/lcd.hpp"
#include "geometry/line_aligned.hpp"
#include "geometry/prototype.hpp"

#include <cstdint>
#include <vector>

namespace canopy {

struct Mbvt;

/// Records of K float fields by lane, 8 lanes to a group, each group's K fields side by side (8
/// floats each), so that a test of 8 lanes reads one run of memory from one pointer (with an array
/// per field the hot loops kept one pointer each, which spilled to the stack). The layout
/// BoxLanes and LcdLanes share.
template <std::size_t K>
struct FieldLanes {
  static constexpr std::uint32_t kWidth = 8;
  static constexpr std::size_t kFields = K;
  static constexpr std::size_t kGroupFloats = K * kWidth;
  LineAlignedVector<float> data;
  /// Where field k of lane `lane` lies in `data`.
  static std::size_t index(std::size_t lane, int k) {
    return lane / kWidth * kGroupFloats + static_cast<std::size_t>(k) * kWidth + lane % kWidth;
  }
  float& at(std::size_t lane, int k) { return data[index(lane, k)]; }
  float at(std::size_t lane, int k) const { return data[index(lane, k)]; }
  /// The group holding lane `lane` (a multiple of kWidth): field k of its 8 lanes at + 8 k.
  const float* group(std::size_t lane) const { return &data[lane / kWidth * kGroupFloats]; }
  /// Room for `lanes` lanes, whole groups; the caller sets every lane.
  std::size_t resize_lanes(std::size_t lanes) {
    data.resize((lanes + kWidth - 1) / kWidth * kGroupFloats);
    return data.size() / kGroupFloats * kWidth;
  }
};

/// Axis-aligned boxes by lane (lo x, y, z, hi x, y, z: 192 bytes a group). Lanes no box was set
/// in hold an empty box (meeting nothing).
struct BoxLanes : FieldLanes<6> {
  void assign_empty(std::size_t lanes);
  void set(std::size_t lane, const Box3f& b) {
    at(lane, 0) = b.lo.x, at(lane, 1) = b.lo.y, at(lane, 2) = b.lo.z;
    at(lane, 3) = b.hi.x, at(lane, 4) = b.hi.y, at(lane, 5) = b.hi.z;
  }
  Box3f get(std::size_t lane) const {
    return Box3f{{at(lane, 0), at(lane, 1), at(lane, 2)}, {at(lane, 3), at(lane, 4), at(lane, 5)}};
  }
};

/// LCD boxes (centred form, geometry/lcd.hpp) by lane (cx, cy, ax, ay, hu, hv, z_lo, z_hi: 256
/// bytes a group), so that 8 LCD tests read their boxes with 8 loads (collision/lanes/lcd_lanes.hpp)
/// rather than gathering 8 records and transposing them. Lanes no box was set in hold an empty
/// LCD box.
struct LcdLanes : FieldLanes<8> {
  void assign_empty(std::size_t lanes);
  void set(std::size_t lane, const LcdCentred& b) {
    at(lane, 0) = b.cx, at(lane, 1) = b.cy, at(lane, 2) = b.ax, at(lane, 3) = b.ay;
    at(lane, 4) = b.hu, at(lane, 5) = b.hv, at(lane, 6) = b.z_lo, at(lane, 7) = b.z_hi;
  }
  LcdCentred get(std::size_t lane) const {
    return LcdCentred{at(lane, 0), at(lane, 1), at(lane, 2), at(lane, 3),
                      at(lane, 4), at(lane, 5), at(lane, 6), at(lane, 7)};
  }
};

/// What the CPU pass reads of a cluster, on one cache line (copies of Cluster's and the tree's
/// fields, side by side): from a 52-byte record and three arrays a cluster pair's first loads
/// waited on up to four lines (bench_detect: the pass about 7 % faster on one).
struct alignas(64) PassCluster {
  Box3f box;  // Cluster::box
  /// The box around its organs' boxes (their least lo and greatest hi, so an organ box that
  /// misses it misses every one of them, exactly).
  Box3f around;
  std::uint32_t first = 0, count = 0;  // Cluster::first, count: its organs in cluster_organs
  std::uint32_t lane = 0;              // its first organ lane (OrganLanes::organ_first)
  std::uint32_t has_free = 0;          // Mbvt::cluster_has_free
};
static_assert(sizeof(PassCluster) == 64);

struct OrganLanes {
  static constexpr std::uint32_t kWidth = BoxLanes::kWidth;
  /// Cluster c's k-th organ (cluster_organs[c.first + k]) at lane organ_first[c] + k; each
  /// cluster's run padded to a multiple of kWidth, with kWidth lanes more after the last.
  std::vector<std::uint32_t> organ_first;
  BoxLanes organs;
  /// Per cluster: what the pass reads of it (fill_organ_lanes, fill_cluster_lanes).
  std::vector<PassCluster, LineAlignedAllocator<PassCluster>> pass;
  /// Per cluster: its root's LCD box, lcd_centred(nodes[root].box), side by side with the other
  /// clusters' (the pass tests cluster pairs' roots without going through the cluster's index).
  std::vector<LcdCentred> roots;
  /// Plant p's k-th cluster's box at lane cluster_first[p] + k, padded the same way, and its
  /// root's LCD box (roots[c]) at the same lane of root_lanes.
  std::vector<std::uint32_t> cluster_first;
  BoxLanes clusters;
  LcdLanes root_lanes;
};

/// Lays the lanes out for the tree's clusters and plants, every box empty.
void lay_out_lanes(OrganLanes& lanes, const Mbvt& m);
/// Cluster c's organ lanes, from its organs' OBBs, its root's LCD box, and its pass record but
/// its box (fill_cluster_lanes sets that).
void fill_organ_lanes(OrganLanes& lanes, const Mbvt& m, std::uint32_t c);
/// Plant p's cluster lanes from its clusters' boxes (fit_plant_bound sets those) and roots
/// (fill_organ_lanes sets those), and its clusters' boxes in their pass records.
void fill_cluster_lanes(OrganLanes& lanes, const Mbvt& m, std::uint32_t p);

}  // namespace canopy
