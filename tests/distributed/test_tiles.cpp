// Tiles for tiled runs: balanced by plant count, every plant owned once, plants on a border
// split by id, halos exactly the plants within reach of a strip (checked by brute force), and
// tiles_holding the mirror of tile_region.
#include "distributed/tiles.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace canopy;

namespace {

std::vector<PlantPlacement> random_field(std::uint64_t seed, std::size_t n, double w, double h) {
  std::mt19937_64 g(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<PlantPlacement> out(n);
  for (auto& p : out) p.x = std::round(u(g) * w * 4) / 4, p.y = u(g) * h;  // x on a grid: ties on borders
  return out;
}

}  // namespace

TEST_CASE("tiles: balanced, owned once, strips along the longer extent") {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const std::size_t n = 1 + seed * 7 % 90;
    const bool wide = seed % 2;
    const auto plants = random_field(seed, n, wide ? 30 : 3, wide ? 3 : 30);
    for (int tiles : {1, 2, 3, 4, 7, 200}) {
      const Tiling t = make_tiling(plants, tiles);
      if (n > 1) CHECK(t.axis == (wide ? 0 : 1));
      REQUIRE(t.owner.size() == n);
      std::vector<std::size_t> count(static_cast<std::size_t>(tiles), 0);
      for (int o : t.owner) ++count[static_cast<std::size_t>(o)];
      CHECK(count == t.owned_count);
      const auto [lo, hi] = std::minmax_element(count.begin(), count.end());
      CHECK(*hi - *lo <= 1);
      // Strips in order: every plant of tile k lies at or before every plant of tile k + 1,
      // ties broken by id.
      for (std::size_t a = 0; a < n; ++a)
        for (std::size_t b = 0; b < n; ++b)
          if (t.owner[a] < t.owner[b]) {
            const double ca = t.coordinate(plants[a]), cb = t.coordinate(plants[b]);
            CHECK((ca < cb || (ca == cb && a < b)));
          }
    }
  }
}

TEST_CASE("tiles: regions hold their own plants and exactly those within the halo") {
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const auto plants = random_field(seed, 60, 20, 2);
    for (int tiles : {2, 3, 5}) {
      const Tiling t = make_tiling(plants, tiles);
      for (double halo : {0.0, 0.5, 3.0}) {
        for (int k = 0; k < tiles; ++k) {
          const auto region = tile_region(t, plants, k, halo);
          CHECK(std::is_sorted(region.begin(), region.end()));
          for (std::size_t p = 0; p < plants.size(); ++p) {
            const double c = t.coordinate(plants[p]);
            const bool own = t.owner[p] == k;
            const bool near = c >= t.lo[static_cast<std::size_t>(k)] - halo &&
                              c <= t.hi[static_cast<std::size_t>(k)] + halo;
            const bool held = std::binary_search(region.begin(), region.end(), static_cast<std::uint32_t>(p));
            CHECK(held == (own || near));
            const auto holding = tiles_holding(t, plants, p, halo);
            CHECK(std::count(holding.begin(), holding.end(), k) == (held && !own ? 1 : 0));
          }
        }
      }
    }
  }
}

TEST_CASE("tiles: more tiles than plants leaves empty tiles with empty regions") {
  const std::vector<PlantPlacement> plants{{0, 0, 0, 1, {}, {}}, {1, 0, 0, 2, {}, {}}};
  const Tiling t = make_tiling(plants, 4);
  CHECK(t.owner == std::vector<int>{0, 1});
  CHECK(tile_region(t, plants, 2, 10).empty());
  CHECK(tile_region(t, plants, 3, 10).empty());
  CHECK(tile_region(t, plants, 0, 10) == std::vector<std::uint32_t>{0, 1});
}

TEST_CASE("tiles: plants on one coordinate at a border go to different tiles by id") {
  const std::vector<PlantPlacement> plants{
      {0, 0, 0, 1, {}, {}}, {1, 0, 0, 2, {}, {}}, {1, 0.2, 0, 3, {}, {}}, {2, 0, 0, 4, {}, {}}};
  const Tiling t = make_tiling(plants, 2);
  CHECK(t.owner == std::vector<int>{0, 0, 1, 1});
  CHECK(t.hi[0] == t.lo[1]);
}
