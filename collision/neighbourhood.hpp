#pragma once
/// What lies near a turning organ, for the turn search: a uniform grid over plant origins and
/// each plant's current horizontal reach, so the organs that a turn about a joint could sweep
/// into are found without a pass over the stand. Reaches are updated for the plants whose organs
/// moved after every resolution round.
#include "geometry/prototype.hpp"
#include "geometry/stand.hpp"

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace canopy {

class Neighbourhood {
 public:
  Neighbourhood(const Stand& stand, PrototypeLibrary& lib);
  /// New reaches for the plants flagged in `plants`.
  void update(const Stand& stand, PrototypeLibrary& lib, const std::vector<std::uint8_t>& plants);
  /// Plants whose organs may come within `r` metres of point (x, y) (relative to stand_origin).
  std::vector<std::int32_t> plants_near(const Stand& stand, double x, double y, double r) const;

 private:
  double cell_ = 1;
  std::unordered_map<std::int64_t, std::vector<std::int32_t>> cells_;
  std::vector<float> reach_;  // per plant: largest horizontal distance of an organ bound from the origin
  float max_reach_ = 0;
  std::int64_t key(std::int64_t i, std::int64_t j) const { return i * 73856093LL ^ j * 19349663LL; }
};

}  // namespace canopy
