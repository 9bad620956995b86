// Detection against brute force on seeded random stands (nothing missed, nothing extra), levels
// nested, results independent of the thread count.
#include "collision/broad_phase.hpp"
#include "helpers.hpp"

#include <random>
#include <set>

using namespace canopy;
using namespace canopy::test;

namespace {

std::string describe(const std::vector<Contact>& want, const std::vector<Contact>& got) {
  std::vector<Contact> missed, extra;
  std::set_difference(want.begin(), want.end(), got.begin(), got.end(), std::back_inserter(missed));
  std::set_difference(got.begin(), got.end(), want.begin(), want.end(), std::back_inserter(extra));
  std::string s = "missed:";
  for (const Contact& c : missed) s += " " + std::to_string(c.organ_a) + "-" + std::to_string(c.organ_b);
  s += " extra:";
  for (const Contact& c : extra) s += " " + std::to_string(c.organ_a) + "-" + std::to_string(c.organ_b);
  return s;
}

}  // namespace

TEST_CASE("exact level equals brute force on seeded random stands, both directions") {
  auto cpu = make_cpu_backend();
  std::size_t total = 0, between = 0, within = 0;
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    const Stand s = random_stand(seed);
    DetectRequest req;
    for (const KindMask& collide : {default_collide_kinds(), parse_collide_kinds("all")}) {
      req.collide = collide;
      const Contacts c = cpu->detect(s, req);
      const std::vector<Contact> want = brute_force_exact(s, collide);
      INFO("seed " << seed << " plants " << s.plant_count() << " organs " << s.organ_count());
      CHECK_MESSAGE(c.pairs == want, describe(want, c.pairs));
      total += want.size();
      for (const Contact& k : want) (k.plant_a == k.plant_b ? within : between)++;
      REQUIRE(c.counts[3]);
      CHECK(c.counts[3]->total() == c.pairs.size());
    }
  }
  MESSAGE("contacts checked: " << total << " (" << between << " between plants, " << within << " within)");
  CHECK(between > 50);  // the stands are dense enough to test something
  CHECK(within > 0);
}

TEST_CASE("inside crowded plants too: the exact level equals brute force") {
  // Leaves stacked on one side of short internodes cross each other and the stem.
  auto cpu = make_cpu_backend();
  std::size_t within = 0;
  for (std::uint64_t seed = 60; seed <= 63; ++seed) {
    GrowRequest req;
    req.grammar = source("grammars/tomato.yaml");
    for (const char* o : {"phyllotaxis=15", "internode_min=0.015", "internode_max=0.02", "insertion_min=20"})
      req.load.overrides.push_back(parse_override(o));
    req.steps = 14;
    PlantPlacement p;
    p.seed = seed;
    req.plants = {p};
    p.x = 0.25, p.seed = seed + 100;
    req.plants.push_back(p);
    const Stand s = grow_stand(req);
    for (const KindMask& collide : {default_collide_kinds(), parse_collide_kinds("all")}) {
      DetectRequest dr;
      dr.collide = collide;
      const Contacts c = cpu->detect(s, dr);
      const auto want = brute_force_exact(s, collide);
      INFO("seed " << seed);
      CHECK_MESSAGE(c.pairs == want, describe(want, c.pairs));
      within += c.counts[3]->within;
    }
  }
  MESSAGE("contacts within plants: " << within);
  CHECK(within > 20);
}

TEST_CASE("with a clearance, the exact level equals brute-force distances") {
  auto cpu = make_cpu_backend();
  for (std::uint64_t seed = 20; seed <= 23; ++seed) {
    const Stand s = random_stand(seed, 8);
    DetectRequest req;
    req.clearance = 0.005f;
    const Contacts c = cpu->detect(s, req);
    const auto want = brute_force_exact(s, req.collide, req.clearance);
    INFO("seed " << seed);
    CHECK_MESSAGE(c.pairs == want, describe(want, c.pairs));
    req.clearance = 0;
    CHECK(cpu->detect(s, req).pairs.size() <= c.pairs.size());
  }
}

TEST_CASE("each level's organ pairs contain the next level's") {
  auto cpu = make_cpu_backend();
  for (std::uint64_t seed = 30; seed <= 35; ++seed) {
    const Stand s = random_stand(seed);
    DetectRequest req;
    PrototypeLibrary lib;
    const Mbvt m = build_mbvt(s, lib, MbvtConfig{});
    std::vector<std::int32_t> cluster_of(s.organ_count(), -1);
    for (std::size_t c = 0; c < m.clusters.size(); ++c)
      for (std::uint32_t k = m.clusters[c].first; k < m.clusters[c].first + m.clusters[c].count; ++k)
        cluster_of[m.cluster_organs[k]] = static_cast<std::int32_t>(c);
    std::set<std::pair<int, int>> plants, leaves;
    req.level = ContactLevel::plant;
    for (const Contact& c : cpu->detect(s, req).pairs) plants.insert({c.plant_a, c.plant_b});
    req.level = ContactLevel::leaf;
    for (const Contact& c : cpu->detect(s, req).pairs) {
      CHECK(c.organ_a == -1);
      CHECK(plants.count({c.plant_a, c.plant_b}));
      leaves.insert({std::min(c.cluster_a, c.cluster_b), std::max(c.cluster_a, c.cluster_b)});
    }
    req.level = ContactLevel::organ;
    const auto organ = cpu->detect(s, req).pairs;
    for (const Contact& c : organ) {
      CHECK(plants.count({c.plant_a, c.plant_b}));
      const int ca = cluster_of[static_cast<std::size_t>(c.organ_a)],
                cb = cluster_of[static_cast<std::size_t>(c.organ_b)];
      CHECK(leaves.count({std::min(ca, cb), std::max(ca, cb)}));
    }
    req.level = ContactLevel::exact;
    const Contacts exact_detection = cpu->detect(s, req);
    const auto& exact = exact_detection.pairs;
    CHECK(std::is_sorted(exact.begin(), exact.end()));
    CHECK(std::includes(organ.begin(), organ.end(), exact.begin(), exact.end()));
    // The exact detection's counts of the levels above are those levels' lists (each organ pair
    // found once).
    REQUIRE(exact_detection.counts[1]);
    REQUIRE(exact_detection.counts[2]);
    CHECK(exact_detection.counts[1]->total() == leaves.size());
    CHECK(exact_detection.counts[2]->total() == organ.size());
    CHECK(exact_detection.counts[2]->within == count_pairs(organ).within);
  }
}

TEST_CASE("the same contacts on any thread count and on every run") {
  auto cpu = make_cpu_backend();
  const Stand s = random_stand(41);
  DetectRequest req;
  req.threads = 1;
  const auto one = cpu->detect(s, req).pairs;
  req.threads = 2;
  CHECK(cpu->detect(s, req).pairs == one);
  req.threads = 7;
  CHECK(cpu->detect(s, req).pairs == one);
  CHECK(std::is_sorted(one.begin(), one.end()));
}

namespace {

/// Every plant pair p < q whose bounds overlap, tested pair by pair; the tree built on the way.
std::vector<std::pair<std::int32_t, std::int32_t>> all_overlapping_plants(const Stand& s, Mbvt& m) {
  PrototypeLibrary lib;
  m = build_mbvt(s, lib, MbvtConfig{});
  std::vector<std::pair<std::int32_t, std::int32_t>> want;
  for (std::size_t p = 0; p < s.plant_count(); ++p)
    for (std::size_t q = p + 1; q < s.plant_count(); ++q)
      if (plant_bounds_overlap(s, m, p, q))
        want.emplace_back(static_cast<std::int32_t>(p), static_cast<std::int32_t>(q));
  return want;
}

}  // namespace

TEST_CASE("plant pairs from the grid equal all pairs of overlapping bounds") {
  Mbvt m;
  for (std::uint64_t seed = 50; seed <= 53; ++seed) {
    const Stand s = random_stand(seed);
    const auto want = all_overlapping_plants(s, m);
    CHECK(plant_pairs(s, m) == want);
  }
  // Clumps of plants scattered over a field on both sides of the origin (cells of negative
  // index, clumps a few cells wide, cells left empty between them), two on one spot in each.
  std::mt19937_64 g(61);
  std::uniform_real_distribution<double> u(0, 1);
  GrowRequest req;
  req.grammar = source("grammars/tomato.yaml");
  for (int clump = 0; clump < 6; ++clump) {
    const double cx = -30 + 60 * u(g), cy = -30 + 60 * u(g), spread = 0.2 + 2.0 * u(g);
    for (int i = 0; i < 10; ++i) {
      PlantPlacement p;
      p.x = cx + spread * u(g), p.y = cy + spread * u(g), p.rotation_deg = 360 * u(g), p.seed = g() % 1000;
      req.plants.push_back(p);
    }
    req.plants.push_back(req.plants.back());
  }
  req.steps = 10;
  req.lod = 1;
  const Stand s = grow_stand(req);
  const auto want = all_overlapping_plants(s, m);
  CHECK(want.size() > 60);
  CHECK(plant_pairs(s, m) == want);
}

TEST_CASE("one backend detecting stand after stand gives each stand's own answer") {
  // The CPU backend builds each tree into the last one's memory and keeps its exact stage's scratch.
  auto reused = make_cpu_backend();
  for (std::uint64_t seed : {3, 8, 5, 3}) {
    const Stand s = seed % 2 ? random_stand(seed) : row_stand(seed);
    DetectRequest req;
    req.level = seed == 5 ? ContactLevel::organ : ContactLevel::exact;
    CHECK(reused->detect(s, req).pairs == make_cpu_backend()->detect(s, req).pairs);
  }
}

TEST_CASE("curved leaflets: the exact level equals brute force, between plants and within them") {
  auto cpu = make_cpu_backend();
  std::size_t between = 0, within = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const Stand s = curved_stand(seed, 1 + static_cast<int>(seed % 3));
    DetectRequest req;
    for (const KindMask& collide : {default_collide_kinds(), parse_collide_kinds("all")}) {
      req.collide = collide;
      const Contacts c = cpu->detect(s, req);
      const std::vector<Contact> want = brute_force_exact(s, collide);
      INFO("seed " << seed << " plants " << s.plant_count() << " organs " << s.organ_count());
      CHECK_MESSAGE(c.pairs == want, describe(want, c.pairs));
      for (const Contact& k : want) (k.plant_a == k.plant_b ? within : between)++;
    }
  }
  MESSAGE("curved contacts checked: " << between << " between plants, " << within << " within");
  CHECK(between > 50);
  CHECK(within > 10);
}
