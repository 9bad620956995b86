#pragma once
/// What lies near a turning organ, for the turn search: a uniform grid over plant origins and
/// each plant's current horizontal reach, so the organs that a turn about a joint could sweep
/// into are found without a pass over the stand. Reaches are updated for the plants whose organs
/// moved after every resolution round.
#include "geometry/obb.hpp"
#include "geometry/stand.hpp"

#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

namespace canopy {

/// A run of consecutive organs of one plant (a subtree-ordered stretch, so usually one place) and
/// a sphere around their bounds, in the plant's frame: whole runs are passed over at once.
struct OrganRun {
  Vec3f centre;
  float radius = 0;  // every organ bound's sphere (OBB centre, radius) lies inside
  Vec3f lo, hi;      // and inside this box (tighter for a run stretched along a leaf)
  std::uint32_t first = 0, end = 0;
};

class Neighbourhood {
 public:
  static constexpr std::uint32_t kRunLength = 16;
  /// From every organ's current OBB (`boxes`, no clearance, in its plant's frame).
  Neighbourhood(const Stand& stand, std::span<const Obb> boxes, int threads);
  /// New reaches and runs for the plants flagged in `plants` (their boxes refitted first).
  void update(const Stand& stand, std::span<const Obb> boxes, const std::vector<std::uint8_t>& plants,
              int threads);
  /// Plants whose organs may come within `r` metres of point (x, y) (relative to stand_origin).
  std::vector<std::int32_t> plants_near(const Stand& stand, double x, double y, double r) const;
  /// The organ runs of a plant, in organ order.
  std::span<const OrganRun> runs(std::int32_t plant) const {
    const auto p = static_cast<std::size_t>(plant);
    return {runs_.data() + run_first_[p], runs_.data() + run_first_[p + 1]};
  }

 private:
  double cell_ = 1;
  std::unordered_map<std::int64_t, std::vector<std::int32_t>> cells_;
  std::vector<float> reach_;  // per plant: largest horizontal distance of an organ bound from the origin
  float max_reach_ = 0;
  std::vector<OrganRun> runs_;
  std::vector<std::uint32_t> run_first_;  // per plant + 1
  void fit_plant(const Stand& stand, std::span<const Obb> boxes, std::size_t plant);
  std::int64_t key(std::int64_t i, std::int64_t j) const { return i * 73856093LL ^ j * 19349663LL; }
};

}  // namespace canopy
