#pragma once
/// A planned turn of a petiole, rachis or peduncle segment spread over the joints of its chain,
/// so that a large turn looks like a bend rather than a kink. The turn search picks the mover,
/// axis and angle by cost as always (resolution/turn_search.hpp); here a turn by theta about axis a
/// at mover k becomes, where it can, m turns by theta / m about a at k and the m - 1 segments
/// above it in its chain (each joint's rotation about its own current position, so the chain
/// arches), each within its own joint limit. The bent pose is then checked against everything
/// it could reach, as the search checks its own: every organ of the turned subtree that met
/// something must be clear of it, and no organ that moves may meet anything it did not meet
/// before. Where no spread passes, the search's own turn stays. The same plan on every backend
/// and thread count (each turn's spread is decided on its own, in plan order).
#include "resolution/bend_chain.hpp"
#include "resolution/turn_search.hpp"

#include <cstddef>
#include <vector>

namespace canopy {

struct SpreadStats {
  std::size_t spread = 0;             // turns spread over several joints
  std::size_t joints = 0;             // joints those turns became
  std::size_t kinked = 0;             // turns above the bend step left at one joint (no spread passed)
  std::vector<std::uint32_t> unbent;  // movers of turns past their own limit that no spread could take
};

/// `turns` (one round's plan) with each turn of more than config.bend_step_deg spread over its
/// chain where a spread passes the checks above. A turn the search found only because its chain
/// could take it (past the mover's own limit, TurnSearch::Candidate::chain_deg) is dropped
/// where no spread passes (its mover listed in SpreadStats::unbent): resolution then searches
/// that mover within its own limit (TurnSearch::unbendable), and its contacts wait for the next
/// round.
std::vector<Turn> spread_turns(const TurnSearch& search, const std::vector<Turn>& turns, int threads,
                               SpreadStats* stats = nullptr);

}  // namespace canopy
