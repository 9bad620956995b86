// A tile's stand merged from its own plants and its halo, grown apart, equals the same plants
// grown in one go: every organ record, transform, parameter, joint limit and plant record.
#include "distributed/region.hpp"
#include "lsystem/grow.hpp"

#include <doctest/doctest.h>

#include <cstring>
#include <random>

using namespace canopy;

namespace {

std::string grammar() {
  if (const char* e = std::getenv("CANOPY_SOURCE_DIR")) return std::string(e) + "/grammars/tomato.yaml";
  return std::string(CANOPY_SOURCE_DIR) + "/grammars/tomato.yaml";
}

}  // namespace

TEST_CASE("region: own and halo plants merged equal one growth of all of them") {
  GrowRequest all;
  all.grammar = grammar();
  all.steps = 12;
  std::mt19937_64 g(5);
  for (int i = 0; i < 9; ++i)
    all.plants.push_back(
        {0.3 * i, 0, 37.0 * i, g() % 100, {}, i % 3 == 0 ? std::optional<int>(9) : std::nullopt});
  const Stand whole = grow_stand(all);
  for (std::uint64_t split :
       {0b000000000ull, 0b101010101ull, 0b111100000ull, 0b000011111ull, 0b010011010ull}) {
    GrowRequest own = all, halo = all;
    own.plants.clear(), halo.plants.clear();
    std::vector<std::uint32_t> own_ids, halo_ids;
    for (std::uint32_t p = 0; p < 9; ++p) {
      if ((split >> p) & 1) own_ids.push_back(p), own.plants.push_back(all.plants[p]);
      else halo_ids.push_back(p), halo.plants.push_back(all.plants[p]);
    }
    const Stand merged = merge_region(grow_stand(own), own_ids, grow_stand(halo), halo_ids);
    REQUIRE(merged.organ_count() == whole.organ_count());
    REQUIRE(merged.plant_count() == whole.plant_count());
    CHECK(std::memcmp(merged.organs.data(), whole.organs.data(), whole.organs.size() * sizeof(OrganRecord)) ==
          0);
    CHECK(std::memcmp(merged.transforms.data(), whole.transforms.data(),
                      whole.transforms.size() * sizeof(Affine3f)) == 0);
    CHECK(merged.params == whole.params);
    CHECK(merged.joint_limit_deg == whole.joint_limit_deg);
    for (std::size_t p = 0; p < whole.plant_count(); ++p) {
      const PlantRecord &a = merged.plants[p], &b = whole.plants[p];
      CHECK(a.first_organ == b.first_organ);
      CHECK(a.organ_count == b.organ_count);
      CHECK(a.first_leaf == b.first_leaf);
      CHECK(a.leaf_count == b.leaf_count);
      CHECK(a.seed == b.seed);
      CHECK(a.steps == b.steps);
      CHECK(merged.grammars[static_cast<std::size_t>(a.grammar)] ==
            whole.grammars[static_cast<std::size_t>(b.grammar)]);
    }
  }
}
