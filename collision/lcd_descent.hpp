#pragma once
/// The descent of two clusters' LCD trees together (Ding et al. 2019 §3.3), shared by the CPU
/// backend and the CUDA organ-pairs kernel (CANOPY_HD): one implementation. It stops at node
/// pairs of at most kBlockOrgans organs a side and hands those over as a block, whose organ
/// pairs collision/organ_blocks.hpp tests flat: a tomato's compound leaf (at most 12 organs)
/// is one block at its root, and only larger clusters descend.
#include "collision/mbvt.hpp"
#include "geometry/hd.hpp"
#include "geometry/lcd.hpp"

#include <cstdint>

namespace canopy {

/// Organs a side at or below which two nodes make one block: the flat organ-box tests of a whole
/// 12-organ compound leaf against another cost less than descending to 4-organ leaves
/// (bench_detect).
inline constexpr std::uint32_t kBlockOrgans = 16;

/// Calls on_block(node_a, node_b) for each pair of nodes, of at most kBlockOrgans organs a side
/// or leaves of the trees, whose boxes overlap (b's cluster carried into a's plant frame by
/// `offset`); the larger node is split first. The roots' boxes are known to overlap (the caller
/// found the cluster pair by that test).
template <typename OnBlock>
CANOPY_HD inline void descend_lcd_trees(const LcdNode* nodes, std::uint32_t root_a, std::uint32_t root_b,
                                        Vec3f offset, OnBlock&& on_block) {
  constexpr int kStack = 64;  // at most the two trees' depths together: far below this
  std::uint32_t stack[kStack][2];
  int top = 0;
  stack[0][0] = root_a, stack[0][1] = root_b, top = 1;
  while (top > 0) {
    --top;
    const std::uint32_t ia = stack[top][0], ib = stack[top][1];
    const LcdNode& na = nodes[ia];
    const LcdNode& nb = nodes[ib];
    const bool roots =
        ia == root_a && ib == root_b;  // only the first pair: children differ from their parents
    if (!roots && !lcd_overlap(na.box, nb.box, offset)) continue;
    const bool split_a = na.left >= 0 && na.count > kBlockOrgans,
               split_b = nb.left >= 0 && nb.count > kBlockOrgans;
    if (!split_a && !split_b) {
      on_block(na, nb);
      continue;
    }
    if (top + 2 > kStack) continue;  // trees of this depth do not occur (2^32 organs per cluster)
    if (split_a && (!split_b || na.count >= nb.count)) {
      stack[top][0] = static_cast<std::uint32_t>(na.left), stack[top][1] = ib, ++top;
      stack[top][0] = static_cast<std::uint32_t>(na.right), stack[top][1] = ib, ++top;
    } else {
      stack[top][0] = ia, stack[top][1] = static_cast<std::uint32_t>(nb.left), ++top;
      stack[top][0] = ia, stack[top][1] = static_cast<std::uint32_t>(nb.right), ++top;
    }
  }
}

}  // namespace canopy
