#pragma once
/// What the rays of one direction found, as whole counts (so the same on any thread count): hits
/// on the stand, its leaflets, each plant, each plant's leaflets, each organ kind and each height
/// layer; and, for the standard errors, the number of sampling pairs whose two rays disagree on
/// each of those (the collapsed-strata variance estimator, below).
#include "geometry/hd.hpp"
#include "geometry/organ_kind.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace canopy::light {

inline constexpr std::size_t kKinds = kOrganKindNames.size();

/// What one ray met: nothing (plant -1), or an organ of a plant and kind at a height layer.
struct Outcome {
  std::int32_t plant = -1;
  std::int32_t layer = -1;
  std::uint8_t kind = 0;
  bool leaflet = false;
  CANOPY_HD bool hit() const { return plant >= 0; }
};

/// The counters of a tally, by field; a device counts into one flat array of them
/// (tally_slot), the host into Tally's members.
enum class TallyField : int {
  hits,
  hits_diff,
  leaf,
  leaf_diff,
  kind,
  kind_diff,
  plant,
  plant_diff,
  plant_leaf,
  plant_leaf_diff,
  layer,
  layer_diff
};

/// Where counter (f, i) lies in the flat array of a stand of `plants` and `layers` layers.
CANOPY_HD inline std::uint64_t tally_slot(TallyField f, std::uint64_t i, std::uint64_t plants,
                                          std::uint64_t layers) {
  constexpr std::uint64_t k = kKinds;
  const std::uint64_t p0 = 4 + 2 * k, l0 = p0 + 4 * plants;
  switch (f) {
    case TallyField::hits: return 0;
    case TallyField::hits_diff: return 1;
    case TallyField::leaf: return 2;
    case TallyField::leaf_diff: return 3;
    case TallyField::kind: return 4 + i;
    case TallyField::kind_diff: return 4 + k + i;
    case TallyField::plant: return p0 + i;
    case TallyField::plant_diff: return p0 + plants + i;
    case TallyField::plant_leaf: return p0 + 2 * plants + i;
    case TallyField::plant_leaf_diff: return p0 + 3 * plants + i;
    case TallyField::layer: return l0 + i;
    case TallyField::layer_diff: return l0 + layers + i;
  }
  return 0;
}
CANOPY_HD inline std::uint64_t tally_slots(std::uint64_t plants, std::uint64_t layers) {
  return 4 + 2 * kKinds + 4 * plants + 2 * layers;
}

/// One ray's counts: `count(field, index)` adds one.
template <class Count>
CANOPY_HD inline void count_ray(const Outcome& a, Count& count) {
  if (!a.hit()) return;
  count(TallyField::hits, 0);
  count(TallyField::plant, static_cast<std::uint64_t>(a.plant));
  count(TallyField::kind, a.kind);
  count(TallyField::layer, static_cast<std::uint64_t>(a.layer));
  if (a.leaflet)
    count(TallyField::leaf, 0), count(TallyField::plant_leaf, static_cast<std::uint64_t>(a.plant));
}

/// A pair of neighbouring cells' counts for the variance (below): each event on which the two
/// rays disagree.
template <class Count>
CANOPY_HD inline void count_pair(const Outcome& a, const Outcome& b, Count& count) {
  if (a.hit() != b.hit()) count(TallyField::hits_diff, 0);
  if (a.leaflet != b.leaflet) count(TallyField::leaf_diff, 0);
  if (!a.hit() && !b.hit()) return;
  if (a.plant != b.plant) {
    if (a.hit()) count(TallyField::plant_diff, static_cast<std::uint64_t>(a.plant));
    if (b.hit()) count(TallyField::plant_diff, static_cast<std::uint64_t>(b.plant));
  }
  const std::int32_t la = a.leaflet ? a.plant : -1, lb = b.leaflet ? b.plant : -1;
  if (la != lb) {
    if (la >= 0) count(TallyField::plant_leaf_diff, static_cast<std::uint64_t>(la));
    if (lb >= 0) count(TallyField::plant_leaf_diff, static_cast<std::uint64_t>(lb));
  }
  const int ka = a.hit() ? a.kind : -1, kb = b.hit() ? b.kind : -1;
  if (ka != kb) {
    if (ka >= 0) count(TallyField::kind_diff, static_cast<std::uint64_t>(ka));
    if (kb >= 0) count(TallyField::kind_diff, static_cast<std::uint64_t>(kb));
  }
  const std::int32_t ya = a.hit() ? a.layer : -1, yb = b.hit() ? b.layer : -1;
  if (ya != yb) {
    if (ya >= 0) count(TallyField::layer_diff, static_cast<std::uint64_t>(ya));
    if (yb >= 0) count(TallyField::layer_diff, static_cast<std::uint64_t>(yb));
  }
}

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
    count_ray(a, *this);
  }
  /// A pair of neighbouring cells' rays (both already add()ed).
  void add_pair(const Outcome& a, const Outcome& b) { count_pair(a, b, *this); }

  /// Adds one to counter (f, i).
  void operator()(TallyField f, std::uint64_t i) {
    switch (f) {
      case TallyField::hits: ++hits; break;
      case TallyField::hits_diff: ++hits_diff; break;
      case TallyField::leaf: ++leaf; break;
      case TallyField::leaf_diff: ++leaf_diff; break;
      case TallyField::kind: ++kind[i]; break;
      case TallyField::kind_diff: ++kind_diff[i]; break;
      case TallyField::plant: ++plant[i]; break;
      case TallyField::plant_diff: ++plant_diff[i]; break;
      case TallyField::plant_leaf: ++plant_leaf[i]; break;
      case TallyField::plant_leaf_diff: ++plant_leaf_diff[i]; break;
      case TallyField::layer: ++layer[i]; break;
      case TallyField::layer_diff: ++layer_diff[i]; break;
    }
  }

  /// The tally of `rays` rays from the flat counters a device made (tally_slot's order).
  static Tally from_slots(const std::uint64_t* c, std::uint64_t rays, std::size_t plants,
                          std::size_t layers) {
    Tally t(plants, layers);
    t.rays = rays;
    const auto at = [&](TallyField f, std::uint64_t i) { return c[tally_slot(f, i, plants, layers)]; };
    t.hits = at(TallyField::hits, 0), t.hits_diff = at(TallyField::hits_diff, 0);
    t.leaf = at(TallyField::leaf, 0), t.leaf_diff = at(TallyField::leaf_diff, 0);
    for (std::size_t k = 0; k < kKinds; ++k)
      t.kind[k] = at(TallyField::kind, k), t.kind_diff[k] = at(TallyField::kind_diff, k);
    for (std::size_t p = 0; p < plants; ++p) {
      t.plant[p] = at(TallyField::plant, p), t.plant_diff[p] = at(TallyField::plant_diff, p);
      t.plant_leaf[p] = at(TallyField::plant_leaf, p);
      t.plant_leaf_diff[p] = at(TallyField::plant_leaf_diff, p);
    }
    for (std::size_t l = 0; l < layers; ++l)
      t.layer[l] = at(TallyField::layer, l), t.layer_diff[l] = at(TallyField::layer_diff, l);
    return t;
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
