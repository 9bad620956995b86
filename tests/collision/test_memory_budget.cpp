// The contact lists bounded by memory: plant pairs counted before the list is made, the CPU
// pass's lists stopped where they outgrow it (resolution's bound: tests/resolution/test_resolve.cpp).
#include "collision/broad_phase.hpp"
#include "collision/memory_budget.hpp"
#include "tests/collision/helpers.hpp"

#include <doctest/doctest.h>

using namespace canopy;
using namespace canopy::test;

TEST_CASE("plant pairs counted without a list: as many as the list holds, stopping past a bound") {
  for (std::uint64_t seed = 50; seed <= 53; ++seed) {
    const Stand s = random_stand(seed);
    PrototypeLibrary lib;
    const Mbvt m = build_mbvt(s, lib, MbvtConfig{});
    const std::uint64_t all = plant_pairs(s, m).size();
    CHECK(count_plant_pairs(s, m) == all);
    if (all > 2) CHECK(count_plant_pairs(s, m, 1) == 2);
    CHECK(count_plant_pairs(s, m, all) == all);
  }
  const Stand spot = on_one_spot(12, 6);
  PrototypeLibrary lib;
  CHECK(count_plant_pairs(spot, build_mbvt(spot, lib, MbvtConfig{})) == 66);
}

TEST_CASE("detection refuses plant pairs or contact lists past its memory, with a clear message") {
  // Eight plants on one spot: 28 plant pairs, hundreds of organ pairs.
  const Stand s = on_one_spot(8);
  auto cpu = make_cpu_backend();
  DetectRequest req;
  req.memory_limit = static_cast<std::size_t>(27 * kBytesPerPlantPair);
  CHECK(failure([&] {
          cpu->detect(s, req);
        }).starts_with("the plants' bounds meet in more than 27 pairs (plants on or near one spot?)"));
  req.memory_limit =
      static_cast<std::size_t>(28 * kBytesPerPlantPair);  // the pairs fit, their contacts do not
  CHECK(failure([&] { cpu->detect(s, req); }).starts_with("detection stopped after "));
  req.memory_limit = std::size_t{1} << 30;
  const Contacts c = cpu->detect(s, req);
  CHECK(c.pairs.size() > 28);
  // The same answer as with no bound at all (the machine's memory).
  req.memory_limit = 0;
  CHECK(cpu->detect(s, req).pairs == c.pairs);
}
