#pragma once
/// Which organ pairs of a block (two nodes handed over by descend_lcd_trees, or one cluster with
/// itself) go on to the adjacency and OBB tests: those whose organs' axis-aligned boxes
/// (obb_aabb) meet. This is the definition both backends keep, written once here (CANOPY_HD):
/// the CPU backend runs the same box test on 8 pairs at once over boxes kept in lanes
/// (collision/lanes/organ_rows.hpp), the CUDA organ-pairs kernel the same conjunction (boxes meet, not
/// adjacent, OBBs overlap) with the boxes tested last, and the tests hold all of them to the same
/// pairs (tests/collision/lanes/test_organ_rows.cpp, tests/cuda).
#include "collision/mbvt.hpp"
#include "collision/mbvt_fit.hpp"
#include "geometry/hd.hpp"
#include "geometry/obb.hpp"

#include <cstdint>

namespace canopy {

/// A box that meets nothing, to grow boxes around others from.
CANOPY_HD inline Box3f empty_box() { return Box3f{{3e38f, 3e38f, 3e38f}, {-3e38f, -3e38f, -3e38f}}; }

/// Grows `around` to hold box b: the least lo and greatest hi, b's value first so that a NaN one
/// leaves `around` as it was. An organ box that misses a box grown around others misses each of
/// them, exactly.
CANOPY_HD inline void grow_around(Box3f& around, const Box3f& b) {
  around.lo = {min_f(b.lo.x, around.lo.x), min_f(b.lo.y, around.lo.y), min_f(b.lo.z, around.lo.z)};
  around.hi = {max_f(b.hi.x, around.hi.x), max_f(b.hi.y, around.hi.y), max_f(b.hi.z, around.hi.z)};
}

/// The box around the organ boxes under node n (grow_around): a row of a block whose box misses
/// it is passed over whole without changing which pairs come out.
template <typename BoxOf>
CANOPY_HD inline Box3f box_around(const LcdNode& n, BoxOf&& box_of) {
  Box3f around = empty_box();
  for (std::uint32_t y = n.first; y < n.first + n.count; ++y) grow_around(around, box_of(y));
  return around;
}

/// Calls on_pair(organ_a, organ_b) for organ x under node na and y under nb (positions in
/// cluster_organs) whose boxes meet, b's moved by `offset`; box_of(position) gives an organ's box.
template <typename BoxOf, typename OnPair>
CANOPY_HD inline void block_pairs(const std::uint32_t* cluster_organs, const LcdNode& na, const LcdNode& nb,
                                  Vec3f offset, BoxOf&& box_of, OnPair&& on_pair) {
  const Box3f around = box_around(nb, box_of);
  for (std::uint32_t x = na.first; x < na.first + na.count; ++x) {
    const Box3f bx = box_of(x);
    if (!boxes_meet(bx, around, offset)) continue;
    for (std::uint32_t y = nb.first; y < nb.first + nb.count; ++y)
      if (boxes_meet(bx, box_of(y), offset))
        on_pair(static_cast<std::int32_t>(cluster_organs[x]), static_cast<std::int32_t>(cluster_organs[y]));
  }
}

/// The same for the pairs x < y of one cluster's organs (positions first .. first + count).
template <typename BoxOf, typename OnPair>
CANOPY_HD inline void own_pairs(const std::uint32_t* cluster_organs, std::uint32_t first, std::uint32_t count,
                                BoxOf&& box_of, OnPair&& on_pair) {
  for (std::uint32_t x = first; x < first + count; ++x) {
    const Box3f bx = box_of(x);
    for (std::uint32_t y = x + 1; y < first + count; ++y)
      if (boxes_meet(bx, box_of(y), Vec3f{0, 0, 0}))
        on_pair(static_cast<std::int32_t>(cluster_organs[x]), static_cast<std::int32_t>(cluster_organs[y]));
  }
}

}  // namespace canopy
