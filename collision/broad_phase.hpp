#pragma once
/// Broad phase over plants: a uniform grid of cell size twice the largest plant radius over the
/// plant origins (any layout: rows, double rows, positions files), giving the plant pairs whose
/// bounds overlap.
#include "collision/mbvt.hpp"
#include "geometry/stand.hpp"

#include <cstdint>
#include <utility>
#include <vector>

namespace canopy {

/// Whether the bounds of plants p and q (vertical cylinders about their origins) overlap.
bool plant_bounds_overlap(const Stand& stand, const Mbvt& m, std::size_t p, std::size_t q);

/// Plant pairs (p < q) whose bounds overlap, sorted.
std::vector<std::pair<std::int32_t, std::int32_t>> plant_pairs(const Stand& stand, const Mbvt& m);
/// How many plant pairs plant_pairs would give, counted without a list; counting stops at
/// `stop_after` + 1 (for a check against a bound, collision/memory_budget.hpp).
std::uint64_t count_plant_pairs(const Stand& stand, const Mbvt& m, std::uint64_t stop_after = UINT64_MAX);

/// A flag per plant: it holds a pair of organs taking part that are not adjacent, so it meets
/// itself at the plant level (the tree's shape alone decides). With `only`, unflagged plants
/// get 0.
std::vector<std::uint8_t> plants_with_free_pairs(const Stand& stand, const Mbvt& m,
                                                 const std::vector<std::uint8_t>* only = nullptr);

/// The plant level as both backends run it: the grid's plant pairs (p < q) and each plant with
/// itself (p, p) where it holds a pair of organs that may meet, sorted; `count` gets the level's
/// numbers between and within plants. With `active` (a flag per plant), only pairs with a
/// flagged plant.
std::vector<std::pair<std::int32_t, std::int32_t>> plant_level(
    const Stand& stand, const Mbvt& m, LevelCount& count, const std::vector<std::uint8_t>* active = nullptr);

}  // namespace canopy
