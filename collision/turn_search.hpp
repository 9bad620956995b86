#pragma once
/// The turn of one organ (with everything distal to it) about its joint that separates it from
/// the organs it met: the smallest angle, to within ResolveConfig::angle_tolerance_deg, on a few
/// candidate axes tried together in increasing angle (the axis that swings the organ straight
/// away from what it met first, then its pitch and in-plane axes both ways), within its joint
/// limit. Separation means the exact test with the resolution clearance finds nothing (or, at
/// the organ level, the OBBs grown by the clearance no longer overlap).
#include "collision/exact.hpp"
#include "collision/joints.hpp"
#include "collision/resolve_policy.hpp"

#include <cstdint>
#include <optional>
#include <vector>

namespace canopy {

struct Turn {
  std::uint32_t organ = 0;
  Mat3d local;          // the joint's local rotation after the turn (Joints::set_local)
  double angle_deg = 0; // this round's turn
};

struct TurnSearch {
  const Stand& stand;
  const Joints& joints;
  PrototypeLibrary& lib;
  const ResolveConfig& config;
  KindMask collide;
  float clearance = 0;  // separation the search asks for (the larger of both clearances)

  /// The turn of `mover` that separates every pair (x, y) of `met` (x in the mover's subtree),
  /// or nothing when no angle within the joint limit does.
  std::optional<Turn> find(std::uint32_t mover, const std::vector<std::pair<std::int32_t, std::int32_t>>& met,
                           ExactScratch& scratch) const;
};

}  // namespace canopy
