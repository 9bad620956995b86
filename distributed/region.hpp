#pragma once
/// A tile's stand from its own plants and its halo plants, grown apart: the two interleaved by
/// global plant id, with organ, leaf and grammar numbers rebased (the same stand as growing all
/// of them in one go, which the tiled run would otherwise do twice for its own plants).
#include "geometry/stand.hpp"

#include <cstdint>
#include <vector>

namespace canopy {

/// Plants of `own` (global ids `own_ids`, ascending) and of `halo` (`halo_ids`, ascending,
/// disjoint from `own_ids`) in ascending global id. stand_origin is left to the caller.
Stand merge_region(const Stand& own, const std::vector<std::uint32_t>& own_ids, const Stand& halo,
                   const std::vector<std::uint32_t>& halo_ids);

}  // namespace canopy
