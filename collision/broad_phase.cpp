#include "collision/broad_phase.hpp"
#include "collision/mbvt_fit.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace canopy {

bool plant_bounds_overlap(const Stand& s, const Mbvt& m, std::size_t p, std::size_t q) {
  return plant_bounds_meet(m.plants[p], m.plants[q], s.plants[q].x - s.plants[p].x,
                           s.plants[q].y - s.plants[p].y);
}

namespace {

/// Calls `visit(p, q)` for the plant pairs (p < q) whose bounds overlap, in no set order, while it
/// returns true.
template <typename Visit>
void visit_plant_pairs(const Stand& s, const Mbvt& m, Visit&& visit) {
  const std::size_t n = s.plant_count();
  if (n < 2) return;
  // Each plant's cell, the plants sorted by cell (row of cells, then cell in the row, then
  // plant): the cells a plant's bound may reach, a 3 x 3 block around its own, are three runs of
  // that order, one per row of cells. Taking the plants in that order, where each run starts
  // only moves on, so one cursor per row keeps it (no hash map, no list per cell, no search).
  const double cell = std::max(2.0 * static_cast<double>(m.max_radius), 1e-3);
  struct Placed {
    std::int64_t iy, ix;
    std::int32_t plant;
    bool operator<(const Placed& o) const {
      return iy != o.iy ? iy < o.iy : ix != o.ix ? ix < o.ix : plant < o.plant;
    }
  };
  std::vector<Placed> sorted(n);
  for (std::size_t p = 0; p < n; ++p)
    sorted[p] = {static_cast<std::int64_t>(std::floor(s.plants[p].y / cell)),
                 static_cast<std::int64_t>(std::floor(s.plants[p].x / cell)), static_cast<std::int32_t>(p)};
  std::sort(sorted.begin(), sorted.end());
  std::size_t run[3] = {0, 0, 0};  // where the run of row dy - 1 starts
  for (const Placed& at : sorted) {
    const auto p = static_cast<std::size_t>(at.plant);
    for (int dy = 0; dy < 3; ++dy) {
      const std::int64_t iy = at.iy + dy - 1;
      std::size_t& k = run[dy];
      while (k < n && sorted[k] < Placed{iy, at.ix - 1, -1}) ++k;
      for (std::size_t j = k; j < n && sorted[j].iy == iy && sorted[j].ix <= at.ix + 1; ++j) {
        const auto q = static_cast<std::size_t>(sorted[j].plant);
        if (q > p && plant_bounds_overlap(s, m, p, q) && !visit(at.plant, sorted[j].plant)) return;
      }
    }
  }
}

}  // namespace

std::vector<std::pair<std::int32_t, std::int32_t>> plant_pairs(const Stand& s, const Mbvt& m) {
  std::vector<std::pair<std::int32_t, std::int32_t>> out;
  visit_plant_pairs(s, m, [&](std::int32_t p, std::int32_t q) {
    out.emplace_back(p, q);
    return true;
  });
  std::sort(out.begin(), out.end());
  return out;
}

std::uint64_t count_plant_pairs(const Stand& s, const Mbvt& m, std::uint64_t stop_after) {
  std::uint64_t count = 0;
  visit_plant_pairs(s, m, [&](std::int32_t, std::int32_t) { return ++count <= stop_after; });
  return count;
}

std::vector<std::uint8_t> plants_with_free_pairs(const Stand& s, const Mbvt& m,
                                                 const std::vector<std::uint8_t>* only) {
  std::vector<std::uint8_t> self(s.plant_count(), 0);
  for (std::size_t p = 0; p < s.plant_count(); ++p)
    self[p] = m.plant_has_free[p] && (!only || (*only)[p]) ? 1 : 0;
  return self;
}

std::vector<std::pair<std::int32_t, std::int32_t>> plant_level(const Stand& s, const Mbvt& m,
                                                               LevelCount& count,
                                                               const std::vector<std::uint8_t>* active) {
  auto work = plant_pairs(s, m);
  const auto on = [&](std::int32_t p) { return !active || (*active)[static_cast<std::size_t>(p)]; };
  if (active) std::erase_if(work, [&](const auto& w) { return !on(w.first) && !on(w.second); });
  count = {work.size(), 0};
  const std::vector<std::uint8_t> self = plants_with_free_pairs(s, m, active);
  // Each plant with itself merged in before its pairs with later plants (both lists sorted).
  std::vector<std::pair<std::int32_t, std::int32_t>> out;
  out.reserve(work.size() + s.plant_count());
  std::size_t k = 0;
  for (std::size_t p = 0; p < s.plant_count(); ++p) {
    if (self[p]) out.emplace_back(static_cast<std::int32_t>(p), static_cast<std::int32_t>(p)), ++count.within;
    for (; k < work.size() && static_cast<std::size_t>(work[k].first) == p; ++k) out.push_back(work[k]);
  }
  assert(k == work.size() && std::is_sorted(out.begin(), out.end()));
  return out;
}

}  // namespace canopy
