// The CPU backend's 8-at-a-time organ-box tests (collision/lanes/organ_rows.hpp) against the one
// definition both backends share (collision/organ_blocks.hpp, boxes_meet pair by pair): the
// same pairs, compared as sorted lists, on seeded random stands and on boxes made to touch.
#include "collision/broad_phase.hpp"
#include "collision/free_pairs.hpp"
#include "collision/lcd_descent.hpp"
#include "collision/organ_blocks.hpp"
#include "collision/lanes/organ_rows.hpp"
#include "tests/collision/helpers.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <utility>
#include <vector>

using namespace canopy;
using namespace canopy::test;

namespace {

using Pairs = std::vector<std::pair<std::int32_t, std::int32_t>>;

Box3f random_box(std::mt19937& g) {
  std::uniform_real_distribution<float> u(-1, 1), w(0, 0.5f);
  const Vec3f c{u(g), u(g), u(g)}, h{w(g), w(g), w(g)};
  return Box3f{c - h, c + h};
}

/// Every cluster pair the pass looks at (plant pairs of the plant level, clusters whose roots'
/// LCD boxes overlap) and every cluster with itself: candidates by the shared definition and by
/// the lanes (lane_small_cluster_pairs too, for two clusters of one block each). `blocks` counts
/// the blocks below the clusters' roots, `small_pairs` the pairs lane_small_cluster_pairs found.
void compare_candidates(const Stand& s, const Mbvt& m, std::size_t& pairs, std::size_t& blocks,
                        std::uint32_t* largest = nullptr, std::size_t* small_pairs = nullptr) {
  LevelCount count;
  const auto box_of = [&](std::uint32_t pos) { return obb_aabb(m.obbs[m.cluster_organs[pos]]); };
  for (const auto& [p, q] : plant_level(s, m, count)) {
    const Vec3f offset = p == q ? Vec3f{0, 0, 0} : plant_offset(s, p, q);
    const PlantBound& pa = m.plants[static_cast<std::size_t>(p)];
    const PlantBound& pb = m.plants[static_cast<std::size_t>(q)];
    for (std::uint32_t i = pa.first_cluster; i < pa.first_cluster + pa.cluster_count; ++i) {
      const Cluster& ca = m.clusters[i];
      for (std::uint32_t j = p == q ? i : pb.first_cluster; j < pb.first_cluster + pb.cluster_count; ++j) {
        const Cluster& cb = m.clusters[j];
        Pairs shared, lanes;
        const auto into = [](Pairs& out) {
          return [&out](std::int32_t a, std::int32_t b) { out.emplace_back(a, b); };
        };
        if (i == j) {
          // The lanes leave out the adjacent pairs of a cluster whose pairs are masked.
          own_pairs(m.cluster_organs.data(), ca.first, ca.count, box_of, into(shared));
          if (pairs_masked(ca.count))
            std::erase_if(shared, [&](const auto& ab) {
              return adjacent(s.organs[ab.first], ab.first, s.organs[ab.second], ab.second);
            });
          lane_own_pairs(m.lanes, m.cluster_organs.data(), m.free_after.data(), m.lanes.pass[i], into(lanes));
        } else {
          if (!lcd_overlap(m.nodes[ca.root].box, m.nodes[cb.root].box, offset)) continue;
          descend_lcd_trees(
              m.nodes.data(), ca.root, cb.root, offset, [&](const LcdNode& na, const LcdNode& nb) {
                blocks += &na != &m.nodes[ca.root] || &nb != &m.nodes[cb.root];  // below a root
                if (largest) *largest = std::max({*largest, na.count, nb.count});
                block_pairs(m.cluster_organs.data(), na, nb, offset, box_of, into(shared));
                lane_block_pairs(m.lanes, m.cluster_organs.data(), i, ca, na, j, cb, nb, offset, into(lanes));
              });
        }
        std::sort(shared.begin(), shared.end());
        std::sort(lanes.begin(), lanes.end());
        INFO("plants " << p << " " << q << " clusters " << i << " " << j);
        CHECK(shared == lanes);
        pairs += shared.size();
        // Clusters of one block each: the pass takes them whole, with 16-bit masks.
        if (i != j && ca.count <= kBlockOrgans && cb.count <= kBlockOrgans) {
          Pairs small;
          lane_small_cluster_pairs(m.lanes, m.cluster_organs.data(), m.lanes.pass[i], m.lanes.pass[j], offset,
                                   into(small));
          std::sort(small.begin(), small.end());
          CHECK(small == shared);
          if (small_pairs) *small_pairs += small.size();
        }
      }
    }
  }
}

}  // namespace

TEST_CASE(
    "eight lanes at once give boxes_meet's answer lane by lane, touching, empty and NaN boxes included") {
  std::mt19937 g(31);
  std::uniform_real_distribution<float> u(-1, 1);
  int met = 0, missed = 0;
  for (int round = 0; round < 3000; ++round) {
    const Box3f a = random_box(g);
    const Vec3f offset = round % 2 ? Vec3f{u(g), u(g), 0} : Vec3f{0, 0, 0};
    BoxLanes lanes;
    lanes.assign_empty(24);
    for (std::uint32_t k = 0; k < 16; ++k) {
      // Lanes 0-5 and 8-13 touch a exactly through one of boxes_meet's six comparisons (as far
      // as the offset's rounding lets them: with a zero offset, exactly), overlapping it along
      // the other axes; the rest are random, lane 7 NaN, lane 15 left empty.
      Box3f b{a.lo - offset, a.hi - offset};
      switch (k % 8) {
        case 0: b.hi.x = a.lo.x - offset.x, b.lo.x = b.hi.x - 0.1f; break;
        case 1: b.lo.x = a.hi.x - offset.x, b.hi.x = b.lo.x + 0.1f; break;
        case 2: b.hi.y = a.lo.y - offset.y, b.lo.y = b.hi.y - 0.1f; break;
        case 3: b.lo.y = a.hi.y - offset.y, b.hi.y = b.lo.y + 0.1f; break;
        case 4: b.hi.z = a.lo.z - offset.z, b.lo.z = b.hi.z - 0.1f; break;
        case 5: b.lo.z = a.hi.z - offset.z, b.hi.z = b.lo.z + 0.1f; break;
        case 6: b = random_box(g); break;
        default: b = random_box(g), b.lo.y = std::numeric_limits<float>::quiet_NaN();
      }
      if (k != 15) lanes.set(k, b);
    }
    for (std::uint32_t first = 0; first <= 8; ++first) {
      const unsigned bits = lanes_meeting(lanes, first, a, offset);
      for (std::uint32_t t = 0; t < 8; ++t) {
        const bool meet = boxes_meet(a, lanes.get(first + t), offset);
        INFO("round " << round << " lane " << first + t);
        CHECK(((bits >> t) & 1u) == (meet ? 1u : 0u));
        (meet ? met : missed)++;
      }
    }
  }
  CHECK(met > 10000);
  CHECK(missed > 10000);
}

TEST_CASE(
    "eight lanes against a moved box give boxes_meet's answer lane by lane, touching, empty and NaN boxes "
    "included") {
  // lanes_meeting_moved: the lanes' boxes unmoved, the one box moved by the offset (a plant's
  // clusters against the other plant's box).
  std::mt19937 g(37);
  std::uniform_real_distribution<float> u(-1, 1);
  int met = 0, missed = 0;
  for (int round = 0; round < 3000; ++round) {
    const Box3f a = random_box(g);
    const Vec3f offset = round % 2 ? Vec3f{u(g), u(g), 0} : Vec3f{0, 0, 0};
    const Box3f moved{a.lo + offset, a.hi + offset};
    BoxLanes lanes;
    lanes.assign_empty(24);
    for (std::uint32_t k = 0; k < 16; ++k) {
      // Lanes 0-5 and 8-13 touch the moved box exactly through one of boxes_meet's six
      // comparisons (its sums a.lo + offset and a.hi + offset, as the test makes them).
      Box3f b = moved;
      switch (k % 8) {
        case 0: b.lo.x = moved.hi.x, b.hi.x = b.lo.x + 0.1f; break;
        case 1: b.hi.x = moved.lo.x, b.lo.x = b.hi.x - 0.1f; break;
        case 2: b.lo.y = moved.hi.y, b.hi.y = b.lo.y + 0.1f; break;
        case 3: b.hi.y = moved.lo.y, b.lo.y = b.hi.y - 0.1f; break;
        case 4: b.lo.z = moved.hi.z, b.hi.z = b.lo.z + 0.1f; break;
        case 5: b.hi.z = moved.lo.z, b.lo.z = b.hi.z - 0.1f; break;
        case 6: b = random_box(g); break;
        default: b = random_box(g), b.hi.x = std::numeric_limits<float>::quiet_NaN();
      }
      if (k % 8 < 6 && round % 3 == 0) {  // one float beyond touching: they miss
        float& f = k % 2 ? (k % 8 < 2   ? b.hi.x
                            : k % 8 < 4 ? b.hi.y
                                        : b.hi.z)
                         : (k % 8 < 2   ? b.lo.x
                            : k % 8 < 4 ? b.lo.y
                                        : b.lo.z);
        f = std::nextafter(f, k % 2 ? -1e30f : 1e30f);
      }
      if (k != 15) lanes.set(k, b);
    }
    for (std::uint32_t first = 0; first <= 8; ++first) {
      const unsigned bits = lanes_meeting_moved(lanes, first, a, offset);
      for (std::uint32_t t = 0; t < 8; ++t) {
        const bool meet = boxes_meet(lanes.get(first + t), a, offset);
        INFO("round " << round << " lane " << first + t);
        CHECK(((bits >> t) & 1u) == (meet ? 1u : 0u));
        (meet ? met : missed)++;
      }
    }
  }
  CHECK(met > 10000);
  CHECK(missed > 10000);
}

TEST_CASE(
    "organ pairs through lanes equal the shared definition on random stands, blocks below the root "
    "included") {
  std::size_t pairs = 0, blocks = 0, sub_blocks = 0, small_pairs = 0;
  std::uint32_t largest_block = 0;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const Stand s = seed % 2 ? random_stand(seed) : row_stand(seed);
    PrototypeLibrary lib;
    MbvtConfig cfg;
    if (seed % 3 == 0) cfg.collide = parse_collide_kinds("all");
    if (seed % 3 == 1) cfg.clearance = 0.01f;
    compare_candidates(s, build_mbvt(s, lib, cfg), pairs, blocks, nullptr, &small_pairs);
    // Stem clusters of up to 40 organs in tree leaves of 3: trees deeper than one block, so the
    // descent hands over nodes below the root, whose lanes start anywhere in the cluster's run
    // and are followed by other organs' lanes.
    cfg.stem_cluster = 40;
    cfg.leaf_chunk = 3;
    std::size_t big_blocks = 0;
    compare_candidates(s, build_mbvt(s, lib, cfg), pairs, big_blocks);
    sub_blocks += big_blocks;
    // Every organ outside the compound leaves in one cluster and one tree leaf: blocks of more
    // than 64 organs a side, which the lanes take in slices.
    cfg.collide = parse_collide_kinds("all");
    cfg.stem_cluster = 1000;
    cfg.leaf_chunk = 1000;
    compare_candidates(s, build_mbvt(s, lib, cfg), pairs, big_blocks, &largest_block);
  }
  CHECK(largest_block > 64);
  CHECK(pairs > 1000);
  CHECK(small_pairs > 1000);
  CHECK(blocks == 0);        // a tomato's clusters are one block each
  CHECK(sub_blocks > 1000);  // the larger clusters did descend below their roots
}

TEST_CASE("the clusters found through lanes are those whose boxes meet and whose roots' LCD boxes overlap") {
  // lane_clusters_overlapping against the two definitions, cluster by cluster: for every plant
  // pair of the plant level and every cluster of the first plant, the second plant's clusters
  // from each starting index the pass uses (0 between plants, i + 1 inside one), in order.
  std::size_t found = 0, box_only = 0;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    const Stand s = seed % 2 ? random_stand(seed) : row_stand(seed);
    PrototypeLibrary lib;
    MbvtConfig cfg;
    if (seed % 3 == 1) cfg.clearance = 0.01f;
    if (seed % 4 == 2) cfg.stem_cluster = 3;  // plants of more clusters: several groups of 8
    const Mbvt m = build_mbvt(s, lib, cfg);
    LevelCount count;
    for (const auto& [p, q] : plant_level(s, m, count)) {
      const Vec3f offset = p == q ? Vec3f{0, 0, 0} : plant_offset(s, p, q);
      const PlantBound& pa = m.plants[static_cast<std::size_t>(p)];
      const PlantBound& pb = m.plants[static_cast<std::size_t>(q)];
      for (std::uint32_t i = pa.first_cluster; i < pa.first_cluster + pa.cluster_count; ++i) {
        const std::uint32_t from = p == q ? i + 1 - pb.first_cluster : 0;
        std::vector<std::uint32_t> want, got;
        for (std::uint32_t j = pb.first_cluster + from; j < pb.first_cluster + pb.cluster_count; ++j) {
          if (!boxes_meet(m.clusters[i].box, m.clusters[j].box, offset)) continue;
          if (lcd_overlap(m.nodes[m.clusters[i].root].box, m.nodes[m.clusters[j].root].box, offset))
            want.push_back(j);
          else ++box_only;
        }
        lane_clusters_overlapping(m.lanes, pb, static_cast<std::uint32_t>(q), from, m.clusters[i].box,
                                  m.lanes.roots[i], offset, [&](std::uint32_t j) { got.push_back(j); });
        INFO("seed " << seed << " plants " << p << " " << q << " cluster " << i);
        CHECK(got == want);
        found += want.size();
      }
    }
  }
  CHECK(found > 1000);
  CHECK(box_only > 100);  // the LCD test does leave out clusters whose boxes meet
}
