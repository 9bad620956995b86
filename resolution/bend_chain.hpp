#pragma once
/// The chain a turn may be spread over (resolution/bend_spread.hpp): a petiole, rachis or peduncle
/// segment and the segments above it, and how far a turn spread over them can go within every
/// joint's limit (what the turn search may ask of such a mover, resolution/turn_search.hpp).
#include "resolution/joints.hpp"
#include "resolution/resolve_policy.hpp"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace canopy {

/// Segments of the kinds a chain is made of: petiole, rachis, peduncle (leaflets end a chain).
inline bool chain_kind(OrganKind k) {
  return k == OrganKind::petiole || k == OrganKind::rachis || k == OrganKind::peduncle;
}

/// Organ k and then its parents, nearest first, while they are chain segments resolution may
/// turn, at most `most` of them; none that `planned` marks (turning this round on its own
/// account) where it is given. Just k where k is no chain segment.
inline std::vector<std::uint32_t> bend_chain(const Stand& s, const ResolveConfig& cfg, std::uint32_t k,
                                             int most, const std::vector<std::uint8_t>* planned = nullptr) {
  std::vector<std::uint32_t> c{k};
  if (!chain_kind(s.organs[k].kind)) return c;
  for (std::int32_t p = s.organs[k].parent; p >= 0 && static_cast<int>(c.size()) < most;
       p = s.organs[static_cast<std::size_t>(p)].parent) {
    const OrganKind kind = s.organs[static_cast<std::size_t>(p)].kind;
    if (!chain_kind(kind) || !cfg.movable[static_cast<std::size_t>(kind)]) break;
    if (planned && (*planned)[static_cast<std::size_t>(p)]) break;
    c.push_back(static_cast<std::uint32_t>(p));
  }
  return c;
}

/// The largest turn of mover k that a spread over m of its chain's joints (m from 2 to the
/// chain's length), theta / m at each, keeps within every joint's limit whatever the axis: a
/// joint's angle after a turn by phi is at most its angle now plus phi. 0 where k has no chain.
inline double chain_reach_deg(const Stand& s, const Joints& j, const ResolveConfig& cfg, std::uint32_t k) {
  if (cfg.bend_joints < 2 || !chain_kind(s.organs[k].kind)) return 0;
  const std::vector<std::uint32_t> c = bend_chain(s, cfg, k, cfg.bend_joints);
  double room = 1e300, best = 0;
  for (std::size_t m = 1; m <= c.size(); ++m) {
    room = std::min(room, s.joint_limit_deg[c[m - 1]] - j.angle_deg(c[m - 1]));
    if (m >= 2) best = std::max(best, static_cast<double>(m) * room);
  }
  return std::max(0.0, best);
}

}  // namespace canopy
