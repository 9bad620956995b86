#pragma once
/// What the rays of one direction found, as whole counts (so the same on any thread count): hits
/// on the stand, its leaflets, each plant, each plant's leaflets, each organ kind and each height
/// layer; and, for the standard errors, the number of sampling pairs whose two rays disagree on
/// each of those (the collapsed-strata variance estimator, below).
#include "geometry/organ_kind.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace canopy::light {

inline constexpr std::size_t kKinds = kOrganKindNames.size();

/// What one ray met: nothing (organ -1), or an organ of a plant and kind at a height layer.
struct Outcome {
  std::int32_t plant = -1;
  std::int32_t layer = -1;
  std::uint8_t kind = 0;
  bool leaflet = false;
  bool hit() const { return plant >= 0; }
};

/// Rays are drawn one per cell of a grid (jittered: a uniform point in each cell) and cells are
/// taken in pairs of neighbours. For the indicator y of any event (this ray hit plant p, ...), the
/// estimate is sum(y) / N and Cochran's collapsed-strata estimator of its variance is
/// sum over pairs of (y_a - y_b)^2 / N^2 ("Sampling Techniques", 3rd ed., 1977, section 5A.12):
/// never below the true variance of the jittered grid, and equal on average to the binomial
/// variance when the rays are independent. Each (y_a - y_b)^2 is 0 or 1: a count.
struct Tally {
  std::uint64_t rays = 0;
  std::uint64_t hits = 0, hits_diff = 0;
  std::uint64_t leaf = 0, leaf_diff = 0;
  std::vector<std::uint64_t> plant, plant_diff, plant_leaf, plant_leaf_diff;
  std::array<std::uint64_t, kKinds> kind{}, kind_diff{};
  std::vector<std::uint64_t> layer, layer_diff;

  Tally() = default;
  Tally(std::size_t plants, std::size_t layers)
      : plant(plants, 0), plant_diff(plants, 0), plant_leaf(plants, 0), plant_leaf_diff(plants, 0),
        layer(layers, 0), layer_diff(layers, 0) {}

  void add(const Outcome& a) {
    ++rays;
    if (!a.hit()) return;
    ++hits;
    ++plant[static_cast<std::size_t>(a.plant)];
    ++kind[a.kind];
    ++layer[static_cast<std::size_t>(a.layer)];
    if (a.leaflet) ++leaf, ++plant_leaf[static_cast<std::size_t>(a.plant)];
  }

  /// A pair of neighbouring cells' rays (both already add()ed).
  void add_pair(const Outcome& a, const Outcome& b) {
    if (a.hit() != b.hit()) ++hits_diff;
    if (a.leaflet != b.leaflet) ++leaf_diff;
    if (!a.hit() && !b.hit()) return;
    const bool same_plant = a.plant == b.plant;
    if (!same_plant) {
      if (a.hit()) ++plant_diff[static_cast<std::size_t>(a.plant)];
      if (b.hit()) ++plant_diff[static_cast<std::size_t>(b.plant)];
    }
    const std::int32_t la = a.leaflet ? a.plant : -1, lb = b.leaflet ? b.plant : -1;
    if (la != lb) {
      if (la >= 0) ++plant_leaf_diff[static_cast<std::size_t>(la)];
      if (lb >= 0) ++plant_leaf_diff[static_cast<std::size_t>(lb)];
    }
    const int ka = a.hit() ? a.kind : -1, kb = b.hit() ? b.kind : -1;
    if (ka != kb) {
      if (ka >= 0) ++kind_diff[static_cast<std::size_t>(ka)];
      if (kb >= 0) ++kind_diff[static_cast<std::size_t>(kb)];
    }
    const std::int32_t ya = a.hit() ? a.layer : -1, yb = b.hit() ? b.layer : -1;
    if (ya != yb) {
      if (ya >= 0) ++layer_diff[static_cast<std::size_t>(ya)];
      if (yb >= 0) ++layer_diff[static_cast<std::size_t>(yb)];
    }
  }

  Tally& operator+=(const Tally& o) {
    rays += o.rays, hits += o.hits, hits_diff += o.hits_diff, leaf += o.leaf, leaf_diff += o.leaf_diff;
    for (std::size_t i = 0; i < plant.size(); ++i)
      plant[i] += o.plant[i], plant_diff[i] += o.plant_diff[i], plant_leaf[i] += o.plant_leaf[i],
          plant_leaf_diff[i] += o.plant_leaf_diff[i];
    for (std::size_t i = 0; i < kKinds; ++i) kind[i] += o.kind[i], kind_diff[i] += o.kind_diff[i];
    for (std::size_t i = 0; i < layer.size(); ++i) layer[i] += o.layer[i], layer_diff[i] += o.layer_diff[i];
    return *this;
  }
};

}  // namespace canopy::light
