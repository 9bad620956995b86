#pragma once
/// FCL (the Flexible Collision Library, Debian libfcl-dev) on a canopy stand, for the detection
/// benchmark: one BVHModel<OBBRSS> per organ (FCL transforms are rigid, so organs of different
/// sizes cannot share a prototype model: the closest real setup), a dynamic AABB tree
/// broad-phase manager over the organs, adjacent pairs and other kinds filtered in its callback.
/// No Eigen type crosses this header, so canopy's code keeps its own compile flags.
#include "collision/mbvt.hpp"
#include "geometry/stand.hpp"

#include <utility>
#include <vector>

namespace canopy {

struct FclResult {
  std::vector<std::pair<int, int>> pairs;  // organ pairs (a < b) whose meshes meet, sorted
  double build_s = 0, detect_s = 0;
};

FclResult fcl_collide(const Stand& stand, PrototypeLibrary& lib, const KindMask& collide);

}  // namespace canopy
