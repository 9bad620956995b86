#pragma once
/// The AABB-tree baseline (Ding et al. 2019 Table 3): an axis-aligned box per organ from its
/// transformed mesh vertices, a median-split tree over all organs of the stand, rebuilt after
/// every change. It answers the organ level (box pairs, adjacent pairs left out) so its build,
/// test and update costs can be set beside the MBVT's on the same stand.
#include "collision/contacts.hpp"
#include "collision/mbvt.hpp"
#include "geometry/prototype.hpp"
#include "geometry/stand.hpp"

#include <vector>

namespace canopy {

class AabbTree {
 public:
  /// Boxes from every organ's vertices (relative to stand_origin), then the tree.
  void build(const Stand& stand, PrototypeLibrary& lib, const KindMask& collide, float clearance = 0);
  /// Organ pairs (a < b) whose boxes overlap and that are not adjacent, sorted.
  std::vector<Contact> overlapping_pairs(const Stand& stand) const;
  std::size_t size() const { return ids_.size(); }

 private:
  struct Node {
    float lo[3], hi[3];
    std::int32_t left = -1, right = -1;  // children; -1 at a leaf holding ids_[first, first+count)
    std::uint32_t first = 0, count = 0;
  };
  std::int32_t build_node(std::uint32_t first, std::uint32_t count);
  std::vector<Node> nodes_;
  std::vector<std::uint32_t> ids_;         // organs taking part, reordered by the build
  std::vector<std::array<float, 6>> box_;  // per organ
};

}  // namespace canopy
