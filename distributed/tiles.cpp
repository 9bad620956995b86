#include "distributed/tiles.hpp"

#include <algorithm>
#include <limits>
#include <numeric>

namespace canopy {

Tiling make_tiling(const std::vector<PlantPlacement>& plants, int tiles) {
  Tiling t;
  const std::size_t n = plants.size();
  double x0 = std::numeric_limits<double>::max(), x1 = -x0, y0 = x0, y1 = -x0;
  for (const PlantPlacement& p : plants)
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  t.axis = (n == 0 || x1 - x0 >= y1 - y0) ? 0 : 1;
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return t.coordinate(plants[a]) < t.coordinate(plants[b]);
  });
  const auto count = static_cast<std::size_t>(std::max(1, tiles));
  t.owner.assign(n, 0);
  t.lo.assign(count, std::numeric_limits<double>::infinity());
  t.hi.assign(count, -std::numeric_limits<double>::infinity());
  t.owned_count.assign(count, 0);
  for (std::size_t tile = 0, first = 0; tile < count; ++tile) {
    const std::size_t last = first + n / count + (tile < n % count ? 1 : 0);
    for (std::size_t i = first; i < last; ++i) {
      const PlantPlacement& p = plants[order[i]];
      t.owner[order[i]] = static_cast<int>(tile);
      t.lo[tile] = std::min(t.lo[tile], t.coordinate(p));
      t.hi[tile] = std::max(t.hi[tile], t.coordinate(p));
    }
    t.owned_count[tile] = last - first;
    first = last;
  }
  return t;
}

namespace {

bool near_strip(const Tiling& t, int tile, double c, double halo) {
  const auto k = static_cast<std::size_t>(tile);
  return t.owned_count[k] > 0 && c >= t.lo[k] - halo && c <= t.hi[k] + halo;
}

}  // namespace

std::vector<std::uint32_t> tile_region(const Tiling& t, const std::vector<PlantPlacement>& plants, int tile,
                                       double halo) {
  std::vector<std::uint32_t> out;
  for (std::size_t p = 0; p < plants.size(); ++p)
    if (t.owner[p] == tile || near_strip(t, tile, t.coordinate(plants[p]), halo))
      out.push_back(static_cast<std::uint32_t>(p));
  return out;
}

std::vector<int> tiles_holding(const Tiling& t, const std::vector<PlantPlacement>& plants, std::size_t p,
                               double halo) {
  std::vector<int> out;
  for (int tile = 0; tile < static_cast<int>(t.lo.size()); ++tile)
    if (tile != t.owner[p] && near_strip(t, tile, t.coordinate(plants[p]), halo)) out.push_back(tile);
  return out;
}

}  // namespace canopy
