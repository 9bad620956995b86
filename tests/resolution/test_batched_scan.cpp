// The batched turn search (each level's attempts in bulk, as the CUDA backend runs them on the
// device) against the host's candidate-by-candidate search: the same turns, bit for bit, on
// seeded stands at both contact levels, with and without a clearance, on crowded stands where
// the relaxed pass and the last resort run, and with more axes than one group holds.
#include "resolution/attempt_runner_host.hpp"
#include "resolution/resolve.hpp"
#include "tests/collision/helpers.hpp"

#include <cstring>
#include <vector>

using namespace canopy;
using namespace canopy::test;

namespace {

struct Outcome {
  ResolveResult result;
  Stand stand;
};

/// `lanes` > 1: batches of `batch` contacts, that many planned at once (each on a thread of its
/// own, through the runner's lanes). `stats`: ResolveRequest::statistics.
/// `host_below`: levels of fewer candidates searched on the host (0: every level in bulk).
Outcome run(Stand s, const ResolveConfig& cfg, float clearance, bool bulk, std::size_t lanes = 1,
            std::size_t batch = 8192, bool stats = false, std::size_t host_below = 0,
            std::size_t batch_organs = kDefaultBatchOrgans) {
  auto cpu = make_cpu_backend();
  ResolveRequest req;
  req.batch_organs = batch_organs;
  req.statistics = stats;
  req.config = cfg;
  req.detect.clearance = clearance;
  req.detect.level = cfg.level;
  req.bulk_lanes = lanes;
  req.batch_contacts = batch;
  req.host_levels_below = host_below;
  PrototypeLibrary lib;
  HostAttemptRunner runner(lib, 2, lanes);
  if (bulk) req.attempts = &runner;
  const Contacts first = cpu->detect(s, req.detect);
  ResolveResult r = resolve(s, *cpu, req, first);
  return {std::move(r), std::move(s)};
}

void same(const Outcome& a, const Outcome& b) {
  CHECK(a.result.contacts_before == b.result.contacts_before);
  CHECK(a.result.contacts_after == b.result.contacts_after);
  CHECK(a.result.rounds == b.result.rounds);
  CHECK(a.result.organs_moved == b.result.organs_moved);
  CHECK(a.result.mean_turn_deg == b.result.mean_turn_deg);
  CHECK(a.result.max_turn_deg == b.result.max_turn_deg);
  CHECK(a.result.unresolved.size() == b.result.unresolved.size());
  REQUIRE(a.stand.transforms.size() == b.stand.transforms.size());
  std::size_t differ = 0;
  for (std::size_t k = 0; k < a.stand.transforms.size(); ++k)
    differ += std::memcmp(&a.stand.transforms[k], &b.stand.transforms[k], sizeof(Affine3f)) != 0;
  CHECK(differ == 0);
}

}  // namespace

TEST_CASE("batched turn search: the same turns as the host's search, bit for bit") {
  std::size_t moved = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    INFO("seed " << seed);
    const Stand s = row_stand(seed);
    ResolveConfig cfg;
    const Outcome host = run(s, cfg, 0, false), bulk = run(s, cfg, 0, true);
    same(host, bulk);
    moved += host.result.organs_moved;
  }
  CHECK(moved > 50);  // the stands need real work
}

TEST_CASE("batched turn search: organ level, clearances, crowded stands and many axes") {
  struct Case {
    const char* name;
    std::vector<std::uint64_t> seeds;
    bool crowded = false;
    ContactLevel level = ContactLevel::exact;
    double clearance = ResolveConfig{}.clearance;
    float detect_clearance = 0;
    int axis_fan = ResolveConfig{}.axis_fan;
    double tolerance = ResolveConfig{}.angle_tolerance_deg;
  };
  const Case cases[] = {
      {"organ level", {2, 3}, false, ContactLevel::organ},
      {"detection and resolution clearances", {4, 5}, false, ContactLevel::exact, 0.002, 0.001f},
      {"crowded: relaxed pass, last resort, unresolvable pairs", {11, 12}, true},
      {"more axes than one group of 32", {3}, false, ContactLevel::exact, ResolveConfig{}.clearance, 0, 40},
      // 0.05 degrees: bisections of up to 6 steps, more than one call's worth of speculation.
      {"a fine angle tolerance",
       {2, 6},
       false,
       ContactLevel::exact,
       ResolveConfig{}.clearance,
       0,
       ResolveConfig{}.axis_fan,
       0.05},
  };
  for (const Case& k : cases)
    for (std::uint64_t seed : k.seeds) {
      INFO(k.name << ", seed " << seed);
      ResolveConfig cfg;
      cfg.level = k.level;
      cfg.clearance = k.clearance;
      cfg.axis_fan = k.axis_fan;
      cfg.angle_tolerance_deg = k.tolerance;
      if (k.crowded) cfg.max_rounds = 4;
      const Stand s = k.crowded ? random_stand(seed, 12) : row_stand(seed);
      same(run(s, cfg, k.detect_clearance, false), run(s, cfg, k.detect_clearance, true));
    }
}

TEST_CASE("batched turn search: batches planned at once on several lanes give the same turns") {
  // Small batches, so that a stand of a few hundred contacts makes dozens of them, and lanes
  // taking them in whatever order their threads get to them.
  for (std::uint64_t seed : {1, 4}) {
    INFO("seed " << seed);
    const Stand s = row_stand(seed);
    ResolveConfig cfg;
    const Outcome host = run(s, cfg, 0, false);
    const Outcome one = run(s, cfg, 0, true, 1, 4);
    const Outcome three = run(s, cfg, 0, true, 3, 4);
    same(host, one);
    same(host, three);
    CHECK(host.result.planning == "host search");
    CHECK(one.result.planning == "host attempts, 1 lane");
    CHECK(three.result.planning == "host attempts, 3 lanes");
    CHECK(host.result.contacts_before > 3 * 4);  // more batches than lanes
  }
  INFO("crowded: the relaxed pass and the last resort after lanes");
  ResolveConfig cfg;
  cfg.max_rounds = 4;
  const Stand s = random_stand(11, 12);
  same(run(s, cfg, 0, false), run(s, cfg, 0, true, 4, 5));
}

TEST_CASE("batches whose candidates carry long chains are searched on the host: the same turns") {
  // A threshold of 1 organ a candidate marks every batch as one of long chains.
  const Stand s = row_stand(3);
  ResolveConfig cfg;
  auto cpu = make_cpu_backend();
  Outcome out[2];
  for (int heavy = 0; heavy < 2; ++heavy) {
    Stand t = s;
    ResolveRequest req;
    req.statistics = true;
    req.config = cfg;
    req.bulk_lanes = 2;
    req.batch_contacts = 16;
    req.host_levels_below = 0;
    if (heavy) req.host_carried = 1;
    PrototypeLibrary lib;
    HostAttemptRunner runner(lib, 2, 2);
    req.attempts = &runner;
    const Contacts first = cpu->detect(t, req.detect);
    ResolveResult r = resolve(t, *cpu, req, first);
    std::size_t levels = 0, host_levels = 0;
    for (const PlanLaneStats& l : r.stats.lanes) levels += l.levels, host_levels += l.host_levels;
    CHECK(levels > 0);
    if (heavy) CHECK(host_levels == levels);
    else CHECK(host_levels == 0);
    out[heavy] = {std::move(r), std::move(t)};
  }
  same(out[0], out[1]);
}

TEST_CASE("batches split by the organs their candidates carry give the same turns") {
  // A cap of 40 organs splits nearly every contact into a batch of its own (a petiole carries its
  // whole leaf): the turns are those of whole batches, on the host's search and in lanes.
  for (std::uint64_t seed : {2, 5}) {
    INFO("seed " << seed);
    const Stand s = row_stand(seed);
    ResolveConfig cfg;
    const Outcome whole = run(s, cfg, 0, true, 1, 8192);
    const Outcome split = run(s, cfg, 0, true, 1, 8192, false, 0, 40);
    const Outcome split_lanes = run(s, cfg, 0, true, 3, 8192, false, 0, 40);
    same(whole, split);
    same(whole, split_lanes);
    CHECK(whole.result.organs_moved > 10);
  }
}

TEST_CASE("batched turn search: small levels searched on the host give the same turns") {
  // Thresholds that send a batch's tail to the host partway through (a level's finds then
  // refined on the host, not in the runner's next call), and one that sends every level there.
  struct Case {
    const char* name;
    Stand stand;
    ResolveConfig cfg;
  };
  ResolveConfig crowded;
  crowded.max_rounds = 4;
  const Case cases[] = {{"rows, seed 2", row_stand(2), {}},
                        {"crowded, seed 12", random_stand(12, 12), crowded}};
  for (const Case& k : cases) {
    INFO("case " << k.name);
    const Outcome host = run(k.stand, k.cfg, 0, false);
    std::size_t mixed = 0, handed = 0;  // runs whose lanes searched levels both ways; finds handed over
    for (std::size_t below : {4, 24, 100000}) {
      INFO("host below " << below);
      const Outcome hybrid = run(k.stand, k.cfg, 0, true, 2, 64, true, below);
      same(host, hybrid);
      std::size_t levels = 0, on_host = 0;
      for (const PlanLaneStats& l : hybrid.result.stats.lanes)
        levels += l.levels, on_host += l.host_levels, handed += l.handed_over;
      CHECK(on_host > 0);
      if (below == 100000) CHECK(on_host == levels);
      mixed += on_host < levels;
      REQUIRE(hybrid.result.stats.attempts);
      if (below < 100000) CHECK(hybrid.result.stats.attempts->calls > 0);
    }
    CHECK(mixed >= 1);
    CHECK(handed > 0);  // a switch with the runner's finds still to refine
  }
}

TEST_CASE(
    "resolution statistics: only when asked, every phase and lane and the runner's counts, the same turns") {
  const Stand s = row_stand(1);
  ResolveConfig cfg;
  const Outcome quiet = run(s, cfg, 0, true, 3, 4);
  const Outcome told = run(s, cfg, 0, true, 3, 4, true);
  same(quiet, told);
  CHECK_FALSE(quiet.result.stats.collected);
  CHECK(quiet.result.stats.phases.empty());
  CHECK(quiet.result.stats.lanes.empty());
  CHECK_FALSE(quiet.result.stats.attempts);

  const ResolveStats& st = told.result.stats;
  CHECK(st.collected);
  CHECK(st.threads > 0);
  REQUIRE(st.phases.size() == 12);
  CHECK(st.phases.front().name == "setup");
  CHECK(st.phases[4].name == "scan");
  CHECK(st.phases.back().name == "release");
  REQUIRE(st.lanes.size() == 3);
  std::size_t levels = 0, table_bytes = 0;
  for (const PlanLaneStats& l : st.lanes) levels += l.levels, table_bytes += l.moving_bytes + l.pair_bytes;
  CHECK(levels > 0);
  CHECK(table_bytes > 0);
  REQUIRE(st.attempts);
  CHECK(st.attempts->hardware == "host");
  CHECK(st.attempts->calls > 0);
  CHECK(st.attempts->groups >= st.attempts->calls);

  INFO("the host's search: its lane, no runner");
  const Outcome host = run(s, cfg, 0, false, 1, 8192, true);
  same(quiet, host);
  REQUIRE(host.result.stats.lanes.size() == 1);
  CHECK(host.result.stats.lanes[0].levels > 0);
  CHECK(host.result.stats.lanes[0].moving_bytes == 0);
  CHECK_FALSE(host.result.stats.attempts);
}
