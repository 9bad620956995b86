#pragma once
/// FCL (the Flexible Collision Library, Debian libfcl-dev) on a canopy stand, for the detection
/// benchmark: one BVHModel<OBBRSS> per organ (FCL transforms are rigid, so organs of different
/// sizes cannot share a prototype model: the closest real setup), a dynamic AABB tree
/// broad-phase manager over the organs, adjacent pairs and other kinds filtered in its callback.
/// No Eigen or FCL type crosses this header, so canopy's code keeps its own compile flags.
#include "collision/mbvt.hpp"
#include "geometry/stand.hpp"

#include <memory>
#include <utility>
#include <vector>

namespace canopy {

/// FCL's models and manager over a stand's organs, built once; the query can then be run and
/// timed as often as wanted, beside canopy's (bench_detect alternates the two, so that both see
/// the same stretch of the machine's speed).
class FclScene {
 public:
  /// Builds the models and the manager's tree of the organs of the kinds in `collide`.
  FclScene(const Stand& stand, PrototypeLibrary& lib, const KindMask& collide);
  ~FclScene();
  FclScene(const FclScene&) = delete;
  FclScene& operator=(const FclScene&) = delete;
  /// Seconds the constructor took (the organs' models and the manager's tree).
  double build_s() const;
  /// FCL's answer at the exact level (the manager's collide with the narrow phase): the organ
  /// pairs (a < b) whose meshes meet, sorted.
  std::vector<std::pair<int, int>> query() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace canopy
