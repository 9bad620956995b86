// The masks of a cluster's free pairs (collision/free_pairs.hpp) against adjacent() pair by
// pair: on seeded random stands with clusters of every size about the mask's 64 organs, and on
// clusters laid out by hand (roots, parents outside the cluster, gaps in the ids).
#include "collision/broad_phase.hpp"
#include "collision/free_pairs.hpp"
#include "tests/collision/helpers.hpp"

#include <algorithm>
#include <random>
#include <vector>

using namespace canopy;
using namespace canopy::test;

namespace {

/// Checks every cluster of the tree: each bit of free_after against adjacent(), and the
/// cluster's flag against organs_hold_free_pair. Returns the free pairs seen in masked clusters.
std::size_t check_masks(const Stand& s, const Mbvt& m, std::size_t& unmasked_clusters) {
  std::size_t free = 0;
  REQUIRE(m.free_after.size() == m.cluster_organs.size());
  REQUIRE(m.cluster_has_free.size() == m.clusters.size());
  for (std::size_t c = 0; c < m.clusters.size(); ++c) {
    const Cluster& cl = m.clusters[c];
    CHECK(static_cast<bool>(m.cluster_has_free[c]) ==
          organs_hold_free_pair(s.organs.data(), m.cluster_organs.data(), cl.first, cl.count));
    if (!pairs_masked(cl.count)) {
      ++unmasked_clusters;
      for (std::uint32_t x = 0; x < cl.count; ++x) CHECK(m.free_after[cl.first + x] == ~std::uint64_t{0});
      continue;
    }
    for (std::uint32_t x = 0; x < cl.count; ++x) {
      const std::uint64_t mask = m.free_after[cl.first + x];
      CHECK((cl.count == 64 || (mask >> cl.count) == 0));  // nothing past the cluster's organs
      for (std::uint32_t y = 0; y < cl.count; ++y) {
        const auto a = static_cast<std::int32_t>(m.cluster_organs[cl.first + x]);
        const auto b = static_cast<std::int32_t>(m.cluster_organs[cl.first + y]);
        const bool want = y > x && !adjacent(s.organs[static_cast<std::size_t>(a)], a,
                                             s.organs[static_cast<std::size_t>(b)], b);
        INFO("cluster " << c << " organs " << x << " " << y);
        CHECK(static_cast<bool>((mask >> y) & 1u) == want);
        free += want;
      }
    }
  }
  return free;
}

/// Checks each plant's flag against organs_hold_free_pair over all its organs taking part (the plant
/// level's question, asked pair by pair). Returns the plants flagged with no cluster flagged.
std::size_t check_plant_flags(const Stand& s, const Mbvt& m) {
  std::size_t across_only = 0;
  REQUIRE(m.plant_has_free.size() == s.plant_count());
  for (std::size_t p = 0; p < s.plant_count(); ++p) {
    const PlantBound& pb = m.plants[p];
    bool want = false, any_cluster = false;
    if (pb.cluster_count > 0) {
      const Cluster& first = m.clusters[pb.first_cluster];
      const Cluster& last = m.clusters[pb.first_cluster + pb.cluster_count - 1];
      want = organs_hold_free_pair(s.organs.data(), m.cluster_organs.data(), first.first,
                                   last.first + last.count - first.first);
      for (std::uint32_t c = pb.first_cluster; c < pb.first_cluster + pb.cluster_count; ++c)
        any_cluster |= m.cluster_has_free[c] != 0;
    }
    INFO("plant " << p);
    CHECK(static_cast<bool>(m.plant_has_free[p]) == want);
    across_only += want && !any_cluster;
  }
  CHECK(plants_with_free_pairs(s, m) == m.plant_has_free);
  return across_only;
}

}  // namespace

TEST_CASE("a cluster's free-pair masks mark exactly its pairs that are not adjacent, on random stands") {
  std::size_t free = 0, unmasked = 0;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const Stand s = seed % 2 ? random_stand(seed) : row_stand(seed);
    PrototypeLibrary lib;
    // Stem clusters of the default 8, of 63, 64 and 65 organs (either side of the mask's
    // width) and of every stem organ at once.
    for (int stem : {8, 63, 64, 65, 100000}) {
      MbvtConfig cfg;
      cfg.collide =
          parse_collide_kinds(seed % 2 || stem > 64 ? "all" : "leaflet,petiole,rachis,internode,peduncle");
      cfg.stem_cluster = stem;
      free += check_masks(s, build_mbvt_topology(s, cfg), unmasked);
    }
  }
  CHECK(free > 10000);
  CHECK(unmasked > 0);
}

TEST_CASE("a plant's flag says whether its organs hold a free pair, across clusters too") {
  // Stem organs alone in clusters of 1 or 2 (a child with its parent): their free pairs lie
  // across clusters only; plants of one organ taking part hold none.
  std::size_t across_only = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const Stand s = seed % 2 ? random_stand(seed) : row_stand(seed);
    for (const char* kinds : {"internode", "leaflet,petiole,rachis,internode,peduncle", "all", "fruit"})
      for (int stem : {1, 2, 8}) {
        MbvtConfig cfg;
        cfg.collide = parse_collide_kinds(kinds);
        cfg.stem_cluster = stem;
        across_only += check_plant_flags(s, build_mbvt_topology(s, cfg));
      }
  }
  CHECK(across_only > 0);
}

TEST_CASE(
    "free-pair masks of random forests: roots, parents outside the cluster, gaps in the ids, 1 to 65 "
    "organs") {
  std::mt19937 g(7);
  std::size_t free = 0, adjacent_pairs = 0;
  for (int round = 0; round < 400; ++round) {
    const std::uint32_t n = 1 + static_cast<std::uint32_t>(round % 65);
    // Ids rising with gaps; each organ's parent an earlier organ of the cluster (most often a
    // near one), an organ outside it (one of three ids below the first, or one inside a gap),
    // or -1 (a root).
    std::vector<std::uint32_t> ids(n);
    std::uint32_t id = 10;
    for (std::uint32_t k = 0; k < n; ++k) ids[k] = id, id += 1 + (g() % 4 == 0 ? 1 + g() % 3 : 0);
    std::vector<OrganRecord> organs(id + 1);
    for (std::uint32_t k = 0; k < n; ++k) {
      OrganRecord& r = organs[ids[k]];
      const std::uint32_t pick = g() % 10;
      if (pick < 6 && k > 0)
        r.parent = static_cast<std::int32_t>(ids[k - 1 - g() % std::min<std::uint32_t>(k, pick < 4 ? 2 : k)]);
      else if (pick < 8) r.parent = static_cast<std::int32_t>(g() % 3 * 3);  // outside, below the first id
      else if (pick < 9 && k > 0 && ids[k] - 1 != ids[k - 1])
        r.parent = static_cast<std::int32_t>(ids[k] - 1);  // the id in the gap just below: outside
      else r.parent = -1;
    }
    std::vector<std::uint64_t> masks(n);
    const bool any = free_pair_masks(organs.data(), ids.data(), n, masks.data());
    if (!pairs_masked(n)) {
      for (std::uint64_t m : masks) CHECK(m == ~std::uint64_t{0});
      CHECK(any == organs_hold_free_pair(organs.data(), ids.data(), 0, n));
      continue;
    }
    bool want_any = false;
    for (std::uint32_t x = 0; x < n; ++x)
      for (std::uint32_t y = 0; y < n; ++y) {
        const auto a = static_cast<std::int32_t>(ids[x]), b = static_cast<std::int32_t>(ids[y]);
        const bool adj = adjacent(organs[ids[x]], a, organs[ids[y]], b);
        const bool want = y > x && !adj;
        INFO("round " << round << " organs " << x << " " << y);
        CHECK(static_cast<bool>((masks[x] >> y) & 1u) == want);
        free += want, adjacent_pairs += y > x && adj, want_any |= want;
      }
    CHECK(any == want_any);
  }
  CHECK(free > 10000);
  CHECK(adjacent_pairs > 1000);
}

TEST_CASE("a cluster of one parent and its children holds no free pair, masked or not") {
  // Every pair adjacent (the parent with each child, the children with each other): 64 organs
  // are masked, 65 are not; either way the cluster holds no free pair, as organs_hold_free_pair says.
  for (const std::uint32_t n : {2u, 64u, 65u, 100u}) {
    std::vector<std::uint32_t> ids(n);
    std::vector<OrganRecord> organs(n + 20);
    for (std::uint32_t k = 0; k < n; ++k) ids[k] = 20 + k;
    for (std::uint32_t k = 1; k < n; ++k) organs[ids[k]].parent = static_cast<std::int32_t>(ids[0]);
    organs[ids[0]].parent = 3;  // outside the cluster
    std::vector<std::uint64_t> masks(n);
    INFO("organs " << n);
    CHECK_FALSE(free_pair_masks(organs.data(), ids.data(), n, masks.data()));
    if (pairs_masked(n))
      for (std::uint64_t m : masks) CHECK(m == 0);
    // One grandchild (of three organs or more) makes free pairs: with every child but its parent.
    if (n > 2) {
      organs[ids[n - 1]].parent = static_cast<std::int32_t>(ids[1]);
      CHECK(free_pair_masks(organs.data(), ids.data(), n, masks.data()));
    }
  }
}
