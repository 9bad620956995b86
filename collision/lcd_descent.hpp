#pragma once
/// The descent of two clusters' LCD trees together down to organ pairs (Ding et al. 2019 §3.3),
/// shared by the CPU backend and the CUDA organ-pairs kernel (CANOPY_HD): one implementation.
#include "collision/mbvt.hpp"
#include "geometry/hd.hpp"
#include "geometry/lcd.hpp"

#include <cstdint>

namespace canopy {

/// Calls on_pair(organ_a, organ_b) for each pair of organs under leaf nodes whose boxes overlap
/// (b's cluster carried into a's plant frame by `offset`); the larger node is split first. The
/// roots' boxes are known to overlap (the caller found the cluster pair by that test).
template <typename OnPair>
CANOPY_HD inline void descend_lcd_trees(const LcdNode* nodes, const std::uint32_t* cluster_organs, std::uint32_t root_a,
                                        std::uint32_t root_b, Vec3f offset, OnPair&& on_pair) {
  constexpr int kStack = 64;  // at most the two trees' depths together: far below this
  std::uint32_t stack[kStack][2];
  int top = 0;
  stack[0][0] = root_a, stack[0][1] = root_b, top = 1;
  while (top > 0) {
    --top;
    const std::uint32_t ia = stack[top][0], ib = stack[top][1];
    const LcdNode& na = nodes[ia];
    const LcdNode& nb = nodes[ib];
    const bool roots = ia == root_a && ib == root_b;  // only the first pair: children differ from their parents
    if (!roots && !lcd_overlap(na.box, nb.box, offset)) continue;
    const bool leaf_a = na.left < 0, leaf_b = nb.left < 0;
    if (leaf_a && leaf_b) {
      for (std::uint32_t i = na.first; i < na.first + na.count; ++i)
        for (std::uint32_t j = nb.first; j < nb.first + nb.count; ++j)
          on_pair(static_cast<std::int32_t>(cluster_organs[i]), static_cast<std::int32_t>(cluster_organs[j]));
      continue;
    }
    if (top + 2 > kStack) continue;  // trees of this depth do not occur (2^32 organs per cluster)
    if (!leaf_a && (leaf_b || na.count >= nb.count)) {
      stack[top][0] = static_cast<std::uint32_t>(na.left), stack[top][1] = ib, ++top;
      stack[top][0] = static_cast<std::uint32_t>(na.right), stack[top][1] = ib, ++top;
    } else {
      stack[top][0] = ia, stack[top][1] = static_cast<std::uint32_t>(nb.left), ++top;
      stack[top][0] = ia, stack[top][1] = static_cast<std::uint32_t>(nb.right), ++top;
    }
  }
}

}  // namespace canopy
