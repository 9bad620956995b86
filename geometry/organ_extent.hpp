#pragma once
/// How large an organ may be and how far from its plant's origin, wherever organs come from (the
/// turtle, a stand folder's organs.csv).
namespace canopy {

/// The largest organ size (a prototype parameter, metres) and the farthest an organ's frame may
/// lie from its plant's origin, along any axis. Organ transforms are float: a size that fits a
/// double but not a float became inf (and NaN in the meshes), and products of a few such numbers
/// in the bound and triangle tests overflow long before FLT_MAX. A kilometre-high plant is far
/// inside.
inline constexpr double kMaxOrganExtent = 1e6;

}  // namespace canopy
