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
  double build_s = 0;   // the organs' models and the manager's tree
  double detect_s = 0;  // the query (the manager's collide with the narrow phase): median of the repeats
};

/// FCL's answer at the exact level; the query is run `repeats` times over the same manager (the
/// median time kept; every run must give the same pairs, or this throws).
FclResult fcl_collide(const Stand& stand, PrototypeLibrary& lib, const KindMask& collide, int repeats = 1);

}  // namespace canopy
