#include "collision/broad_phase.hpp"
#include "collision/mbvt_fit.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace canopy {

bool plant_bounds_overlap(const Stand& s, const Mbvt& m, std::size_t p, std::size_t q) {
  return plant_bounds_meet(m.plants[p], m.plants[q], s.plants[q].x - s.plants[p].x, s.plants[q].y - s.plants[p].y);
}

std::vector<std::pair<std::int32_t, std::int32_t>> plant_pairs(const Stand& s, const Mbvt& m) {
  std::vector<std::pair<std::int32_t, std::int32_t>> out;
  const std::size_t n = s.plant_count();
  if (n < 2) return out;
  const double cell = std::max(2.0 * static_cast<double>(m.max_radius), 1e-3);
  const auto key = [](std::int64_t ix, std::int64_t iy) {
    return static_cast<std::uint64_t>(ix) * 0x9e3779b97f4a7c15ULL ^ static_cast<std::uint64_t>(iy);
  };
  struct Cell {
    std::int64_t ix, iy;
    std::vector<std::int32_t> plants;
  };
  std::unordered_map<std::uint64_t, std::vector<Cell>> grid;
  std::vector<std::pair<std::int64_t, std::int64_t>> cell_of(n);
  for (std::size_t p = 0; p < n; ++p) {
    const std::int64_t ix = static_cast<std::int64_t>(std::floor(s.plants[p].x / cell));
    const std::int64_t iy = static_cast<std::int64_t>(std::floor(s.plants[p].y / cell));
    cell_of[p] = {ix, iy};
    auto& bucket = grid[key(ix, iy)];
    auto it = std::find_if(bucket.begin(), bucket.end(), [&](const Cell& c) { return c.ix == ix && c.iy == iy; });
    if (it == bucket.end()) {
      bucket.push_back({ix, iy, {}});
      it = bucket.end() - 1;
    }
    it->plants.push_back(static_cast<std::int32_t>(p));
  }
  for (std::size_t p = 0; p < n; ++p) {
    const auto [ix, iy] = cell_of[p];
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        auto b = grid.find(key(ix + dx, iy + dy));
        if (b == grid.end()) continue;
        for (const Cell& c : b->second) {
          if (c.ix != ix + dx || c.iy != iy + dy) continue;
          for (std::int32_t q : c.plants)
            if (static_cast<std::size_t>(q) > p && plant_bounds_overlap(s, m, p, static_cast<std::size_t>(q)))
              out.emplace_back(static_cast<std::int32_t>(p), q);
        }
      }
  }
  std::sort(out.begin(), out.end());
  return out;
}

bool has_free_pair(const Stand& s, const Mbvt& m, std::uint32_t first, std::uint32_t count) {
  return organs_hold_free_pair(s.organs.data(), m.cluster_organs.data(), first, count);
}

std::vector<std::uint8_t> plants_with_free_pairs(const Stand& s, const Mbvt& m, const std::vector<std::uint8_t>* only) {
  std::vector<std::uint8_t> self(s.plant_count(), 0);
#pragma omp parallel for schedule(dynamic, 16)
  for (std::size_t p = 0; p < s.plant_count(); ++p) {
    const PlantBound& pb = m.plants[p];
    if (pb.cluster_count == 0 || (only && !(*only)[p])) continue;
    // The plant's organs that take part are contiguous in cluster_organs.
    const Cluster& first = m.clusters[pb.first_cluster];
    const Cluster& last = m.clusters[pb.first_cluster + pb.cluster_count - 1];
    self[p] = has_free_pair(s, m, first.first, last.first + last.count - first.first) ? 1 : 0;
  }
  return self;
}

std::vector<std::pair<std::int32_t, std::int32_t>> plant_level(const Stand& s, const Mbvt& m, LevelCount& count,
                                                               const std::vector<std::uint8_t>* active) {
  auto work = plant_pairs(s, m);
  const auto on = [&](std::int32_t p) { return !active || (*active)[static_cast<std::size_t>(p)]; };
  if (active) std::erase_if(work, [&](const auto& w) { return !on(w.first) && !on(w.second); });
  count = {work.size(), 0};
  const std::vector<std::uint8_t> self = plants_with_free_pairs(s, m, active);
  for (std::size_t p = 0; p < s.plant_count(); ++p)
    if (self[p]) work.emplace_back(static_cast<std::int32_t>(p), static_cast<std::int32_t>(p)), ++count.within;
  std::sort(work.begin(), work.end());
  return work;
}

}  // namespace canopy
