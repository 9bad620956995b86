#pragma once
/// The CPU backend's form of collision/organ_blocks.hpp: the same pairs (organ boxes that meet,
/// boxes_meet's very comparisons), found 8 at a time over the boxes kept in lanes
/// (collision/lanes/organ_lanes.hpp) with GCC vector extensions. A row (one organ of a against b's
/// organs) is skipped where the organ's box misses the box around b's organs, which it then
/// misses one by one too (exactly: that box is their least lo and greatest hi). Host only: nvcc
/// never reads this file.
#include "collision/free_pairs.hpp"
#include "collision/lanes/lanes8.hpp"
#include "collision/lanes/lcd_lanes.hpp"
#include "collision/mbvt.hpp"
#include "collision/mbvt_fit.hpp"
#include "collision/lanes/organ_lanes.hpp"

#include <algorithm>
#include <cstdint>

namespace canopy {

namespace lanes_detail {
/// Lanes lane .. lane + 7 copied into one group's layout: an LCD node below a cluster's root
/// starts anywhere in its run (every cluster's and plant's run starts a group).
[[gnu::noinline]] inline void gather_group(const BoxLanes& l, std::uint32_t lane, float* out) {
  for (int k = 0; k < 6; ++k)
    for (std::uint32_t t = 0; t < BoxLanes::kWidth; ++t)
      out[static_cast<std::uint32_t>(k) * BoxLanes::kWidth + t] = l.at(lane + t, k);
}
/// Lanes lane .. lane + 7 in one group's layout: the group itself where `lane` starts one, else
/// gathered into `scratch` (kGroupFloats floats).
inline const float* group_from(const BoxLanes& l, std::uint32_t lane, float* scratch) {
  if (lane % BoxLanes::kWidth == 0) [[likely]]
    return l.group(lane);
  gather_group(l, lane, scratch);
  return scratch;
}
/// boxes_meet(box, box of lane t of group g, offset) for the 8 lanes, as bits.
inline unsigned group_meeting(const float* g, const Box3f& box, Vec3f offset) {
  const auto c = [g](int k) { return load8(g + BoxLanes::kWidth * static_cast<std::size_t>(k)); };
  return bits8((box.lo.x <= c(3) + offset.x) & (c(0) + offset.x <= box.hi.x) & (box.lo.y <= c(4) + offset.y) &
               (c(1) + offset.y <= box.hi.y) & (box.lo.z <= c(5) + offset.z) & (c(2) + offset.z <= box.hi.z));
}
/// boxes_meet(box, box of lane t of group g, {0, 0, 0}) for the 8 lanes, as bits: the same
/// answers as group_meeting with a zero offset (x + 0 compares as x; -0 becomes +0, which
/// compares equal) without its 6 additions of zero, which the compiler must keep.
inline unsigned group_meeting(const float* g, const Box3f& box) {
  const auto c = [g](int k) { return load8(g + BoxLanes::kWidth * static_cast<std::size_t>(k)); };
  return bits8((box.lo.x <= c(3)) & (c(0) <= box.hi.x) & (box.lo.y <= c(4)) & (c(1) <= box.hi.y) &
               (box.lo.z <= c(5)) & (c(2) <= box.hi.z));
}
/// boxes_meet(box of lane t of group g, box, offset) for the 8 lanes, as bits.
inline unsigned group_meeting_moved(const float* g, const Box3f& box, Vec3f offset) {
  const auto c = [g](int k) { return load8(g + BoxLanes::kWidth * static_cast<std::size_t>(k)); };
  return bits8((c(0) <= box.hi.x + offset.x) & (box.lo.x + offset.x <= c(3)) & (c(1) <= box.hi.y + offset.y) &
               (box.lo.y + offset.y <= c(4)) & (c(2) <= box.hi.z + offset.z) & (box.lo.z + offset.z <= c(5)));
}
/// The box of lane t of the run whose first group is g (t may lie in a later group).
inline Box3f run_box(const float* g, std::uint32_t t) {
  const float* at = g + t / BoxLanes::kWidth * BoxLanes::kGroupFloats + t % BoxLanes::kWidth;
  constexpr std::size_t w = BoxLanes::kWidth;
  return Box3f{{at[0], at[w], at[2 * w]}, {at[3 * w], at[4 * w], at[5 * w]}};
}
}  // namespace lanes_detail

/// Bit t set where boxes_meet(box, box of lane `lane + t`, offset) holds.
inline unsigned lanes_meeting(const BoxLanes& l, std::uint32_t lane, const Box3f& box, Vec3f offset) {
  using namespace lanes_detail;
  alignas(32) float scratch[BoxLanes::kGroupFloats];
  return group_meeting(group_from(l, lane, scratch), box, offset);
}

/// lanes_meeting with a zero offset (group_meeting's form without one).
inline unsigned lanes_meeting(const BoxLanes& l, std::uint32_t lane, const Box3f& box) {
  using namespace lanes_detail;
  alignas(32) float scratch[BoxLanes::kGroupFloats];
  return group_meeting(group_from(l, lane, scratch), box);
}

/// Bit t set where boxes_meet(box of lane `lane + t`, box, offset) holds: the lanes' boxes on the
/// other side of the test, `box` the one moved.
inline unsigned lanes_meeting_moved(const BoxLanes& l, std::uint32_t lane, const Box3f& box, Vec3f offset) {
  using namespace lanes_detail;
  alignas(32) float scratch[BoxLanes::kGroupFloats];
  return group_meeting_moved(group_from(l, lane, scratch), box, offset);
}

/// block_pairs over lanes: organs under node na of cluster ca (index ia) against those under nb
/// of cluster cb (index ib). Both sides are sifted 8 at a time first, each organ's box against
/// the box around the other cluster's organs (PassCluster::around): an organ that misses it
/// misses each of them too, exactly, as that box is their least lo and greatest hi and b's side
/// is compared in the very sums of the pair test (a's side against around's hi + offset, which
/// is not below any of b's hi + offset). Only the rows left are tested against b's lanes left,
/// so a compound-leaf pair whose leaves barely cross costs a few vector tests rather than a row
/// per organ. a's side goes in slices of 64 organs (a bit each).
template <typename OnPair>
inline void lane_block_pairs(const OrganLanes& l, const std::uint32_t* cluster_organs, std::uint32_t ia,
                             const Cluster& ca, const LcdNode& na, std::uint32_t ib, const Cluster& cb,
                             const LcdNode& nb, Vec3f offset, OnPair&& on_pair) {
  using lanes_detail::lanes_below;
  constexpr std::uint32_t kW = OrganLanes::kWidth, kSlice = 64;
  const Box3f around_a = l.pass[ia].around;
  const Box3f around_b = l.pass[ib].around;
  const Box3f b_moved{around_b.lo + offset, around_b.hi + offset};
  const std::uint32_t la = l.organ_first[ia] + (na.first - ca.first);
  const std::uint32_t lb = l.organ_first[ib] + (nb.first - cb.first);
  for (std::uint32_t xs = 0; xs < na.count; xs += kSlice) {
    const std::uint32_t x_end = std::min(na.count, xs + kSlice);
    unsigned rows[kSlice / kW];
    unsigned any = 0;
    for (std::uint32_t x0 = xs; x0 < x_end; x0 += kW)
      any |= rows[(x0 - xs) / kW] = lanes_meeting(l.organs, la + x0, b_moved) & lanes_below(x_end, x0);
    if (!any) continue;
    for (std::uint32_t y0 = 0; y0 < nb.count; y0 += kW) {
      const unsigned cols = lanes_meeting(l.organs, lb + y0, around_a, offset) & lanes_below(nb.count, y0);
      if (!cols) continue;
      for (std::uint32_t x0 = xs; x0 < x_end; x0 += kW)
        for (unsigned r = rows[(x0 - xs) / kW]; r; r &= r - 1) {
          const std::uint32_t x = x0 + static_cast<std::uint32_t>(__builtin_ctz(r));
          for (unsigned mask = lanes_meeting(l.organs, lb + y0, l.organs.get(la + x), offset) & cols; mask;
               mask &= mask - 1) {
            const std::uint32_t y = nb.first + y0 + static_cast<std::uint32_t>(__builtin_ctz(mask));
            on_pair(static_cast<std::int32_t>(cluster_organs[na.first + x]),
                    static_cast<std::int32_t>(cluster_organs[y]));
          }
        }
    }
  }
}

/// lane_block_pairs for two whole clusters of at most 2 x 8 organs each (a tomato's compound
/// leaves and stem runs): the same pairs, found with the sifts and rows held in 16-bit masks,
/// so that a cluster pair costs two sifts and a row per organ left, with no loops over slices,
/// groups and rows of groups and no array of rows (bench_detect: the pass about 6 % faster than
/// through lane_block_pairs).
template <typename OnPair>
inline void lane_small_cluster_pairs(const OrganLanes& l, const std::uint32_t* cluster_organs,
                                     const PassCluster& ca, const PassCluster& cb, Vec3f offset,
                                     OnPair&& on_pair) {
  constexpr std::uint32_t kW = OrganLanes::kWidth;
  const auto upto = [](std::uint32_t count) { return (1u << count) - 1; };  // count <= 16
  const Box3f around_a = ca.around;
  const Box3f around_b = cb.around;
  const Box3f b_moved{around_b.lo + offset, around_b.hi + offset};
  using lanes_detail::group_meeting;
  constexpr std::size_t kG = BoxLanes::kGroupFloats;
  // Each cluster's run starts a group: its lanes are read from its first group on.
  const float* ga = l.organs.group(ca.lane);
  const float* gb = l.organs.group(cb.lane);
  // a's organs whose boxes meet the box around b's, then b's that meet the box around a's.
  unsigned rows = group_meeting(ga, b_moved);
  if (ca.count > kW) rows |= group_meeting(ga + kG, b_moved) << kW;
  rows &= upto(ca.count);
  if (!rows) return;
  unsigned cols = group_meeting(gb, around_a, offset);
  if (cb.count > kW) cols |= group_meeting(gb + kG, around_a, offset) << kW;
  cols &= upto(cb.count);
  if (!cols) return;
  const bool low = (cols & 0xffu) != 0, high = cols > 0xffu;
  for (; rows; rows &= rows - 1) {
    const auto x = static_cast<std::uint32_t>(__builtin_ctz(rows));
    const Box3f bx = lanes_detail::run_box(ga, x);
    unsigned meet = low ? group_meeting(gb, bx, offset) : 0u;
    if (high) meet |= group_meeting(gb + kG, bx, offset) << kW;
    for (meet &= cols; meet; meet &= meet - 1)
      on_pair(static_cast<std::int32_t>(cluster_organs[ca.first + x]),
              static_cast<std::int32_t>(
                  cluster_organs[cb.first + static_cast<std::uint32_t>(__builtin_ctz(meet))]));
  }
}

/// Calls on_cluster(j) for plant q's clusters j (global indices) from its local index `from` on
/// whose boxes meet `box` (boxes_meet(box, cluster j's box, offset)) and whose roots' LCD boxes
/// overlap `root` (lcd_overlap(root, roots[j], offset)), in order: the boxes 8 at a time, then,
/// where any of the 8 meet, the LCD boxes 8 at a time (collision/lanes/lcd_lanes.hpp), rather than an
/// LCD test and a branch per cluster whose box meets.
template <typename OnCluster>
inline void lane_clusters_overlapping(const OrganLanes& l, const PlantBound& pb, std::uint32_t q,
                                      std::uint32_t from, const Box3f& box, const LcdCentred& root,
                                      Vec3f offset, OnCluster&& on_cluster) {
  const std::uint32_t l0 = l.cluster_first[q];
  for (std::uint32_t k0 = from / OrganLanes::kWidth * OrganLanes::kWidth; k0 < pb.cluster_count;
       k0 += OrganLanes::kWidth) {
    unsigned mask = lanes_detail::group_meeting(l.clusters.group(l0 + k0), box, offset) &
                    lanes_detail::lanes_below(pb.cluster_count, k0);
    if (k0 < from) mask &= ~0u << (from - k0);
    if (!mask) continue;
    for (mask &= lcd_overlapping8(root, l.root_lanes.group(l0 + k0), offset); mask; mask &= mask - 1)
      on_cluster(pb.first_cluster + k0 + static_cast<std::uint32_t>(__builtin_ctz(mask)));
  }
}

/// Calls on_cluster(i) for plant p's clusters i (global indices) whose boxes meet `box` moved by
/// `offset` (boxes_meet(cluster i's box, box, offset)), in order; for every cluster of p with
/// `all`.
template <typename OnCluster>
inline void lane_clusters_meeting_moved(const OrganLanes& l, const PlantBound& pa, std::uint32_t p,
                                        const Box3f& box, Vec3f offset, bool all, OnCluster&& on_cluster) {
  const std::uint32_t l0 = l.cluster_first[p];
  for (std::uint32_t k0 = 0; k0 < pa.cluster_count; k0 += OrganLanes::kWidth) {
    unsigned mask = lanes_detail::lanes_below(pa.cluster_count, k0);
    if (!all) mask &= lanes_detail::group_meeting_moved(l.clusters.group(l0 + k0), box, offset);
    for (; mask; mask &= mask - 1)
      on_cluster(pa.first_cluster + k0 + static_cast<std::uint32_t>(__builtin_ctz(mask)));
  }
}

/// own_pairs over lanes less the pairs free_after leaves out (collision/free_pairs.hpp, beside
/// cluster_organs): the pairs x < y of the organs of cluster c (its pass record) whose boxes
/// meet and, in a cluster of at most kMaskOrgans organs, that are not adjacent (in a larger one
/// every pair whose boxes meet).
template <typename OnPair>
inline void lane_own_pairs(const OrganLanes& l, const std::uint32_t* cluster_organs,
                           const std::uint64_t* free_after, const PassCluster& c, OnPair&& on_pair) {
  const std::uint32_t l0 = c.lane;
  constexpr std::uint32_t kW = OrganLanes::kWidth;
  if (c.count <= 2 * kW) {
    // A cluster of one or two groups (every tomato cluster): each row against the groups whole,
    // with no branch per row or group (its free_after mask keeps the pairs wanted: bits above x,
    // in the cluster, not adjacent), then the pairs, in the order of the rows below. The rows
    // below skip rows and groups, and those skips are mispredicted branches, dearer than the
    // lane tests they save.
    static_assert(2 * OrganLanes::kWidth <= kMaskOrgans, "the masks must hold these clusters' free pairs");
    unsigned hits[2 * kW];
    unsigned rows = 0;                     // bit x set where row x has a pair
    const float* g0 = l.organs.group(l0);  // the cluster's run starts a group
    for (std::uint32_t x = 0; x + 1 < c.count; ++x) {
      const Box3f bx = lanes_detail::run_box(g0, x);
      unsigned meet = lanes_detail::group_meeting(g0, bx);
      if (c.count > kW) meet |= lanes_detail::group_meeting(g0 + BoxLanes::kGroupFloats, bx) << kW;
      hits[x] = meet & static_cast<unsigned>(free_after[c.first + x]);
      rows |= static_cast<unsigned>(hits[x] != 0) << x;
    }
    for (; rows; rows &= rows - 1)
      for (unsigned x = static_cast<unsigned>(__builtin_ctz(rows)), mask = hits[x]; mask; mask &= mask - 1)
        on_pair(static_cast<std::int32_t>(cluster_organs[c.first + x]),
                static_cast<std::int32_t>(
                    cluster_organs[c.first + static_cast<std::uint32_t>(__builtin_ctz(mask))]));
    return;
  }
  const bool masked = pairs_masked(c.count);
  for (std::uint32_t x = 0; x + 1 < c.count; ++x) {
    const std::uint64_t free = free_after[c.first + x];
    if (!free) continue;
    const Box3f bx = lanes_detail::run_box(l.organs.group(l0), x);
    // Whole groups of 8 lanes from the one holding x + 1 (aligned loads), the organs up to x
    // left out (by the mask, or else by hand).
    for (std::uint32_t y0 = (x + 1) / OrganLanes::kWidth * OrganLanes::kWidth; y0 < c.count;
         y0 += OrganLanes::kWidth) {
      unsigned wanted = masked ? static_cast<unsigned>(free >> y0) & 0xffu : 0xffu;
      if (y0 <= x) wanted &= ~0u << (x + 1 - y0);
      if (!wanted) continue;
      const unsigned meet = lanes_detail::group_meeting(l.organs.group(l0 + y0), bx);
      for (unsigned mask = meet & wanted & lanes_detail::lanes_below(c.count, y0); mask; mask &= mask - 1) {
        const std::uint32_t y = y0 + static_cast<std::uint32_t>(__builtin_ctz(mask));
        on_pair(static_cast<std::int32_t>(cluster_organs[c.first + x]),
                static_cast<std::int32_t>(cluster_organs[c.first + y]));
      }
    }
  }
}

}  // namespace canopy
