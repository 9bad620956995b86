#pragma once
/// Which organ turns for a contact (the resolution policy). Every contact gets an ordered list of
/// candidate movers from both of its organs: the organ itself where its kind may turn, then its
/// ancestors in the structure tree up to (not including) the first organ that may not turn, a
/// fruit or flower handing over to the peduncle that carries it. A candidate whose subtree holds
/// both organs is left out (the pair would turn together). The list is ordered by
///   1. kind rank: leaflet, then peduncle, then rachis, then petiole (the cheapest, most local
///      turn first: a leaflet before its rachis, a rachis segment before its petiole);
///   2. between plants, the organ farther out from its plant's stem first (`outer_first`);
///   3. the smaller subtree (fewer organs carried), then the higher id (the more distal organ).
/// Internodes never turn (docs/design.md "Organ kinds by role"). The first candidate that separates
/// the pair within its joint limit is used; a contact none can separate is unresolvable.
#include "collision/contacts.hpp"
#include "resolution/joints.hpp"
#include "collision/mbvt.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace canopy {

struct ResolveConfig {
  int max_rounds = 30;               // detection rounds before giving up
  int stall_rounds = 5;              // stop when the contact count has not improved for this many rounds
  double clearance = 1e-4;           // metres left between a turned organ and what it met
  double angle_tolerance_deg = 0.5;  // the smallest separating angle is found to within this
  double scan_step_deg = 3;          // angles tried in steps of this before bisection
  int axis_fan = 12;                 // axes across the organ's width-normal plane tried besides the away axis
  ContactLevel level = ContactLevel::exact;  // exact, or organ (OBBs: faster, turns more)
  KindMask movable = default_movable_kinds();
  std::array<int, 7> kind_rank = default_kind_rank();
  /// Cost of a turn = angle x weight: a petiole turn (which carries a whole leaf) must be this
  /// many times smaller than a leaflet turn to be preferred.
  std::array<double, 7> kind_weight = default_kind_weight();
  /// Movers per contact scanned together (policy order). 14 rather than 10: the mature tomato's
  /// 1,000-plant stand (fruit colliding) left 5 contacts with 10, a leaflet wedged in a
  /// neighbour's truss, and none with 14, at no cost on an H200 (10,000 default plants' resolution
  /// 1.34-1.37 s either way; canopy stand --resolve-candidates, docs/tomato.md).
  int candidates = 14;
  bool outer_first = true;
  /// A turn of a petiole, rachis or peduncle segment by more than bend_step_deg is spread over up
  /// to bend_joints joints of its chain, about bend_step_deg each, where the bent pose passes the
  /// search's checks (resolution/bend_spread.hpp); 1: every turn stays at one joint.
  int bend_joints = 6;
  double bend_step_deg = 4;

  /// Throws std::invalid_argument naming the setting that cannot be met: a clearance that is
  /// negative or not finite, an angle step or tolerance or a kind weight that is not a finite
  /// positive number (a NaN step never reaches the joint's reach: the scan would not end), fewer
  /// than one round or candidate, a bend step that is not a finite positive number or fewer than
  /// one bend joint.
  void check() const;

  static KindMask default_movable_kinds();
  static std::array<int, 7> default_kind_rank();
  static std::array<double, 7> default_kind_weight();
};

/// The ordered candidate movers of contact c (may be empty); `why` says why when it is.
std::vector<std::uint32_t> candidate_movers(const Stand& stand, const Joints& joints, const Contact& c,
                                            const ResolveConfig& config, std::string& why);

}  // namespace canopy
