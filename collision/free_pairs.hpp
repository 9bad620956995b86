#pragma once
/// Which organ pairs of one cluster are not adjacent (docs/design.md "Adjacency": a parent and its
/// child, and two children of one parent, touch by construction), as a bit mask per organ, made
/// with the tree's shape (it depends on the stand's structure alone, never on poses): the CPU
/// pass then offers a cluster's own pairs to the OBB test without reading their organ records.
/// Host only.
#include "collision/mbvt_fit.hpp"
#include "geometry/stand.hpp"

#include <cstdint>

namespace canopy {

/// Organs a cluster may have for its pairs to be masked; a larger cluster's masks have every
/// bit set (its pairs are then sifted by adjacent() one by one).
inline constexpr std::uint32_t kMaskOrgans = 64;

/// Whether a cluster of `organs` organs has its pairs masked (its masks' bits are its free pairs).
inline bool pairs_masked(std::uint32_t organs) { return organs <= kMaskOrgans; }

/// For the cluster of organs ids[0, n) (one plant's, in string order): free_after[k] gets bit y
/// set where k < y < n and organs ids[k], ids[y] are not adjacent (every bit when n exceeds
/// kMaskOrgans). Returns whether the cluster holds a pair that is not adjacent
/// (organs_hold_free_pair's answer).
inline bool free_pair_masks(const OrganRecord* organs, const std::uint32_t* ids, std::uint32_t n,
                            std::uint64_t* free_after) {
  if (!pairs_masked(n)) {
    for (std::uint32_t k = 0; k < n; ++k) free_after[k] = ~std::uint64_t{0};
    return organs_hold_free_pair(organs, ids, 0, n);
  }
  // Each organ's parent is looked for among the cluster's earlier organs (where the ids run
  // on without a gap it sits ids[k] - parent places back; otherwise nearest first); children are
  // gathered per parent inside the cluster, and organs whose parent lies outside it (or is -1:
  // a plant's roots count as children of one parent) are grouped by that parent.
  std::int32_t parent[kMaskOrgans];
  int local_parent[kMaskOrgans];
  std::uint64_t children[kMaskOrgans], outside = 0;
  for (std::uint32_t k = 0; k < n; ++k) children[k] = 0;
  for (std::uint32_t k = 0; k < n; ++k) {
    const std::int32_t pa = parent[k] = organs[ids[k]].parent;
    const std::int64_t back = static_cast<std::int64_t>(ids[k]) - pa;
    int j = back > 0 && back <= k && static_cast<std::int32_t>(ids[k - back]) == pa
                ? static_cast<int>(k - back)
                : -1;
    if (j < 0) {
      j = static_cast<int>(k) - 1;
      while (j >= 0 && static_cast<std::int32_t>(ids[j]) != pa) --j;
    }
    local_parent[k] = j;
    (j >= 0 ? children[j] : outside) |= std::uint64_t{1} << k;
  }
  const std::uint64_t in_cluster = n < 64 ? (std::uint64_t{1} << n) - 1 : ~std::uint64_t{0};
  std::uint64_t any = 0;
  for (std::uint32_t k = 0; k < n; ++k) {
    std::uint64_t adjacent_to = children[k];
    if (local_parent[k] >= 0) {
      adjacent_to |= std::uint64_t{1} << local_parent[k] | children[local_parent[k]];
    } else {
      for (std::uint64_t o = outside; o; o &= o - 1) {
        const int y = __builtin_ctzll(o);
        if (parent[y] == parent[k]) adjacent_to |= std::uint64_t{1} << y;
      }
    }
    const std::uint64_t later = k + 1 < 64 ? ~std::uint64_t{0} << (k + 1) : 0;
    any |= free_after[k] = ~adjacent_to & later & in_cluster;
  }
  return any != 0;
}

}  // namespace canopy
