// CPU detection: plant pairs from the grid, cluster (compound-leaf) pairs by LCD boxes, organ
// pairs by OBBs through the LCD trees (down to blocks of at most kBlockOrgans organs a side,
// whose pairs are pre-tested 8 at a time on axis-aligned organ boxes, and whose OBB tests run 8
// pairs at a time), then the exact test;
// inside one plant the same between its clusters (the paper's m(m-1)/2 leaf pairs, §3.4) and
// all pairs within a cluster, with the structure tree's adjacent pairs left out.
#include "collision/backend.hpp"
#include "collision/broad_phase.hpp"
#include "collision/exact.hpp"
#include "collision/lcd_descent.hpp"
#include "collision/memory_budget.hpp"
#include "collision/mbvt_fit.hpp"
#include "collision/lanes/obb_lanes.hpp"
#include "collision/lanes/organ_rows.hpp"
#include "geometry/clock.hpp"
#include "geometry/first_exception.hpp"
#include "geometry/organ_mesh.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <memory>
#include <optional>
#include <stdexcept>

namespace canopy {
namespace {

struct Work {
  std::int32_t p, q;  // plants, p <= q
};

struct Collector {
  std::vector<Contact> leaf, organ;
  LevelCount leaves;
  bool keep_leaves = false;
  /// Told which organs moved (a re-detection): pairs of two unmoved organs are left out here
  /// rather than tested and dropped afterwards.
  const std::vector<std::uint8_t>* moved = nullptr;
  /// Organ pairs waiting for their OBB test, 8 at a time (collision/lanes/obb_lanes.hpp), in two
  /// batches: a full batch is tested only once the next one is full too, so the OBBs it asked
  /// for when its pairs came have had eight pairs' time more to arrive (they are the tree's,
  /// which stay in place until the test). Tested at once, a batch spent about half of its time
  /// on the first loads of its OBBs (bench_detect, one thread).
  static constexpr int kBatches = 2;
  ObbBatch batch[kBatches];
  int filling = 0;  // the batch pairs are added to; the others are full or empty
  /// Adds a pair; tests the other batch where this one fills up.
  void add(const Obb& oa, const Obb& ob, Vec3f off, std::int32_t ia, std::int32_t ib, std::int32_t pa,
           std::int32_t pb) {
    batch[filling].add(oa, ob, off, ia, ib, pa, pb);
    if (!batch[filling].full()) return;
    filling = (filling + 1) % kBatches;
    test(batch[filling]);
  }
  /// Tests both batches (the older first).
  void test_waiting() {
    for (int k = 1; k <= kBatches; ++k) test(batch[(filling + k) % kBatches]);
  }
  void leaf_pair(std::int32_t p, std::int32_t q, std::uint32_t i, std::uint32_t j) {
    (p == q ? leaves.within : leaves.between)++;
    if (keep_leaves)
      leaf.push_back({-1, -1, p, q, static_cast<std::int32_t>(i), static_cast<std::int32_t>(j)});
  }
  /// A batch's OBB tests; the pairs whose OBBs overlap join the organ level. Leaves it empty.
  void test(ObbBatch& waiting) {
    for (unsigned hit = waiting.overlapping(); hit; hit &= hit - 1) {
      const int t = __builtin_ctz(hit);
      Contact c;
      c.organ_a = std::min(waiting.organ_a[t], waiting.organ_b[t]),
      c.organ_b = std::max(waiting.organ_a[t], waiting.organ_b[t]);
      c.plant_a = waiting.plant_a[t], c.plant_b = waiting.plant_b[t];
      organ.push_back(c);
    }
    waiting.size = 0;
  }
};

/// `known_free`: the pair is known not to be adjacent (a cluster's own pair that its free_after
/// mask let through), so the parents are left unread. Inlined where the pass finds its pairs:
/// a call costs the pass time (bench_detect: about 4 %, one thread).
[[gnu::always_inline]] inline void organ_pair(const Mbvt& m, std::int32_t a, std::int32_t b, Vec3f offset_ab,
                                              Collector& out, std::int32_t plant_a, std::int32_t plant_b,
                                              bool known_free = false) {
  // offset_ab moves b into a's plant frame when a is the lower organ; callers pass organs of
  // one plant pair with the lower plant's organ first.
  if (out.moved && !(*out.moved)[static_cast<std::size_t>(a)] && !(*out.moved)[static_cast<std::size_t>(b)])
    return;
  // Organs of two plants are never adjacent; of one plant, their parents decide (the tree's
  // dense copy: a quarter of the records' bytes, so a faster pass than reading the records,
  // prefetched or not).
  if (plant_a == plant_b && !known_free &&
      parents_adjacent(m.parent_of[static_cast<std::size_t>(a)], a, m.parent_of[static_cast<std::size_t>(b)],
                       b))
    return;
  out.add(m.obbs[static_cast<std::size_t>(a)], m.obbs[static_cast<std::size_t>(b)], offset_ab, a, b, plant_a,
          plant_b);
}

/// Asks for plant q's boxes, organ ids and lanes ahead of a work item that needs them (not its
/// organs' parents, which the pass reads for few pairs):
/// the pass waits on memory more than it computes, and the plant pairs come in an order that a
/// prefetch two items ahead covers. Into the second-level cache, not the first: a plant's arrays
/// (about 33 kB at the default level of detail) would push the item at hand's out of the first.
void prefetch_plant(const Stand& s, const Mbvt& m, std::int32_t q) {
  const PlantRecord& pr = s.plants[static_cast<std::size_t>(q)];
  const PlantBound& pb = m.plants[static_cast<std::size_t>(q)];
  const auto lines = [](const void* p, std::size_t bytes) {
    const char* c = static_cast<const char*>(p);
    for (std::size_t k = 0; k < bytes; k += 64) __builtin_prefetch(c + k, 0, 2);
  };
  lines(&m.obbs[pr.first_organ], pr.organ_count * sizeof(Obb));
  if (pb.cluster_count == 0) return;
  const Cluster& c0 = m.clusters[pb.first_cluster];
  const Cluster& c1 = m.clusters[pb.first_cluster + pb.cluster_count - 1];
  lines(&m.lanes.pass[pb.first_cluster], pb.cluster_count * sizeof(PassCluster));
  lines(&m.nodes[c0.first_node], (c1.first_node + c1.node_count - c0.first_node) * sizeof(LcdNode));
  lines(&m.cluster_organs[c0.first], (c1.first + c1.count - c0.first) * sizeof(std::uint32_t));
  const OrganLanes& l = m.lanes;
  const auto lanes = [&](const BoxLanes& b, std::size_t l0, std::size_t l1) {
    lines(b.group(l0),
          (l1 - l0 + BoxLanes::kWidth - 1) / BoxLanes::kWidth * BoxLanes::kGroupFloats * sizeof(float));
  };
  lanes(l.organs, l.organ_first[pb.first_cluster],
        l.organ_first[pb.first_cluster + pb.cluster_count - 1] + c1.count);
  const std::size_t k0 = l.cluster_first[static_cast<std::size_t>(q)], k1 = k0 + pb.cluster_count;
  lanes(l.clusters, k0, k1);
  lines(l.root_lanes.group(k0),
        (k1 - k0 + LcdLanes::kWidth - 1) / LcdLanes::kWidth * LcdLanes::kGroupFloats * sizeof(float));
}

class CpuBackend : public DetectionBackend {
 public:
  std::string name() const override { return "cpu"; }
  /// The threads the caller's runs get (its --threads or OMP_NUM_THREADS), not the machine's.
  std::string device() const override {
    return fmt::format("{} CPU threads", std::max(1, omp_get_max_threads()));
  }

  Contacts detect(const Stand& s, const DetectRequest& req) override {
    check_request(req);
    const double t = now_seconds();
    lib_ = std::make_unique<PrototypeLibrary>();
    // The last detection's tree is built anew in place: its arrays' memory kept (no page
    // faults for a stand no larger than the last); one that failed half-way is dropped.
    if (!tree_) tree_.emplace();
    try {
      rebuild_mbvt(*tree_, s, *lib_, mbvt_config(req));
    } catch (...) {
      tree_.reset();
      throw;
    }
    return run(s, req, now_seconds() - t);
  }

  Contacts redetect(const Stand& s, const DetectRequest& req,
                    const std::vector<std::uint32_t>& moved) override {
    check_request(req);
    if (!tree_ || tree_->obbs.size() != s.organ_count())
      throw std::logic_error("redetect: no tree of this stand from an earlier detect()");
    const double t = now_seconds();
    refit_mbvt(*tree_, s, *lib_, moved, req.threads);
    return run(s, req, now_seconds() - t);
  }

 private:
  std::optional<Mbvt> tree_;
  std::unique_ptr<PrototypeLibrary> lib_;
  std::vector<ExactScratch> scratch_;  // per thread
  // Kept from detection to detection, emptied at the start of each, so that their memory is
  // warm: grown afresh every time (a collector's organ list to tens of thousands of pairs),
  // they cost page faults and regrowth copies wherever the heap had handed its memory back (a
  // process holding little else). The tests' backends reused across stands, levels and thread
  // counts fail if one is left unemptied.
  std::vector<Work> work_;
  std::vector<Collector> per_;  // per thread
  std::vector<Contact> organ_;  // every thread's organ pairs
  std::vector<std::uint8_t> hit_;

  Contacts run(const Stand& s, const DetectRequest& req, double build_s) {
    Contacts out;
    out.level = req.level;
    out.build_s = build_s;
    const Mbvt& m = *tree_;
    PrototypeLibrary& lib = *lib_;
    double t = now_seconds();
    const int threads = req.threads > 0 ? req.threads : omp_get_max_threads();

    // Plant level: pairs of plants whose bounds meet, and each plant with itself; counted first
    // where they might not fit in memory (collision/memory_budget.hpp).
    const std::size_t budget = memory_budget(req.memory_limit);
    if (budget && !req.active_plants)
      if (const std::uint64_t most = most_plant_pairs(budget); count_plant_pairs(s, m, most) > most)
        refuse_plant_pairs(most, budget);
    LevelCount plant_count;
    std::vector<Work>& work = work_;
    work.clear();
    for (const auto& [p, q] : plant_level(s, m, plant_count, req.active_plants)) work.push_back({p, q});
    out.counts[0] = plant_count;
    out.seconds[0] = now_seconds() - t;
    if (req.level == ContactLevel::plant) {
      for (const Work& w : work) out.pairs.push_back({-1, -1, w.p, w.q, -1, -1});
      std::sort(out.pairs.begin(), out.pairs.end());
      return out;
    }

    // Leaf and organ levels, plant pair by plant pair. Told which organs moved, cluster pairs of
    // which neither cluster holds one are passed over, and organ pairs of two unmoved organs are
    // left out (Collector::moved): the caller keeps its answer for those.
    t = now_seconds();
    std::vector<std::uint8_t> cluster_moved;
    if (req.moved_organs) {
      cluster_moved.assign(m.clusters.size(), 0);
#pragma omp parallel for schedule(static, 1024) num_threads(threads)
      for (std::size_t i = 0; i < m.clusters.size(); ++i)
        for (std::uint32_t k = m.clusters[i].first; k < m.clusters[i].first + m.clusters[i].count; ++k)
          if ((*req.moved_organs)[m.cluster_organs[k]]) {
            cluster_moved[i] = 1;
            break;
          }
    }
    const auto passed_over = [&](std::uint32_t i, std::uint32_t j) {
      return !cluster_moved.empty() && !cluster_moved[i] && !cluster_moved[j];
    };
    // A collector per thread (the lists are sorted afterwards, so which thread found a pair
    // does not show in the answer).
    std::vector<Collector>& per = per_;
    per.resize(static_cast<std::size_t>(threads));
    for (Collector& col : per) {
      col.leaf.clear(), col.organ.clear();
      col.leaves = {};
      col.keep_leaves = req.level == ContactLevel::leaf;
      col.moved = req.moved_organs;
      for (ObbBatch& b : col.batch) b.size = 0;
    }
    // The lists stop where they would outgrow the memory (collision/memory_budget.hpp): plants
    // on or near one spot make contacts as the square of their number.
    const std::size_t most =
        budget ? static_cast<std::size_t>(static_cast<double>(budget) / kBytesPerContact) : SIZE_MAX;
    std::atomic<std::size_t> listed{0}, done{0};
    std::atomic<bool> over{false};
    // The first exception met (out of memory inside one huge plant pair, which the budget sees
    // only after it) stops the other threads and is thrown after the region.
    FirstException failed;
#pragma omp parallel for schedule(dynamic, 4) num_threads(threads)
    for (std::size_t w = 0; w < work.size(); ++w) {
      if (over.load(std::memory_order_relaxed) || failed.caught()) continue;
      try {
        const auto [p, q] = work[w];
        if (w + 2 < work.size() && work[w + 2].q != q) prefetch_plant(s, m, work[w + 2].q);
        const PlantBound& pa = m.plants[static_cast<std::size_t>(p)];
        const PlantBound& pb = m.plants[static_cast<std::size_t>(q)];
        const Vec3f offset = p == q ? Vec3f{0, 0, 0} : plant_offset(s, p, q);
        Collector& col = per[static_cast<std::size_t>(omp_get_thread_num())];
        const std::size_t held = col.leaf.size() + col.organ.size();
        // Axis-aligned pre-tests that never reject what the LCD test accepts (lcd_aabb): the other
        // plant's box (8 of p's clusters at a time), then each cluster's.
        lane_clusters_meeting_moved(
            m.lanes, pa, static_cast<std::uint32_t>(p), pb.box, offset, p == q, [&](std::uint32_t i) {
              const PassCluster& ca = m.lanes.pass[i];
              if (p == q && !passed_over(i, i) && ca.has_free) {  // within one cluster: all its pairs
                col.leaf_pair(p, q, i, i);
                if (req.level != ContactLevel::leaf)
                  lane_own_pairs(m.lanes, m.cluster_organs.data(), m.free_after.data(), ca,
                                 [&](std::int32_t a, std::int32_t b) {
                                   organ_pair(m, a, b, offset, col, p, q, pairs_masked(ca.count));
                                 });
              }
              const std::uint32_t from = p == q ? i + 1 - pb.first_cluster : 0;  // local index in plant q
              lane_clusters_overlapping(
                  m.lanes, pb, static_cast<std::uint32_t>(q), from, ca.box, m.lanes.roots[i], offset,
                  [&](std::uint32_t j) {
                    const PassCluster& cb = m.lanes.pass[j];
                    if (passed_over(i, j)) return;
                    col.leaf_pair(p, q, i, j);
                    if (req.level == ContactLevel::leaf) return;
                    const auto block = [&](const LcdNode& na, const LcdNode& nb) {
                      lane_block_pairs(m.lanes, m.cluster_organs.data(), i, m.clusters[i], na, j,
                                       m.clusters[j], nb, offset, [&](std::int32_t x, std::int32_t y) {
                                         organ_pair(m, x, y, offset, col, p, q);
                                       });
                    };
                    // Two clusters of one block each (a tomato's compound leaves): the descent would hand
                    // their roots straight over, and a root spans its cluster's organs; the clusters' own
                    // lanes are taken, the nodes left unread.
                    static_assert(kBlockOrgans == 2 * OrganLanes::kWidth,
                                  "lane_small_cluster_pairs takes clusters of one block");
                    if (ca.count <= kBlockOrgans && cb.count <= kBlockOrgans)
                      lane_small_cluster_pairs(
                          m.lanes, m.cluster_organs.data(), ca, cb, offset,
                          [&](std::int32_t x, std::int32_t y) { organ_pair(m, x, y, offset, col, p, q); });
                    else
                      descend_lcd_trees(m.nodes.data(), m.clusters[i].root, m.clusters[j].root, offset,
                                        block);
                  });
            });
        done.fetch_add(1, std::memory_order_relaxed);
        if (const std::size_t grown = col.leaf.size() + col.organ.size() - held)
          if (listed.fetch_add(grown, std::memory_order_relaxed) + grown > most)
            over.store(true, std::memory_order_relaxed);
      } catch (...) {
        failed.keep();
      }
    }
    failed.rethrow();
    if (over)
      throw std::runtime_error(
          fmt::format("detection stopped after {} of {} plant pairs: its contact lists (over {} pairs) "
                      "outgrew the {:.1f} GB of memory "
                      "available (plants on or near one spot?); spread the plants out or use fewer",
                      done.load(), work.size(), listed.load(), static_cast<double>(budget) / 1e9));
    for (Collector& c : per) c.test_waiting();
    std::vector<Contact> leaf;
    std::vector<Contact>& organ = organ_;
    organ.clear();
    LevelCount leaf_count;
    std::size_t n_leaf = 0;
    for (const Collector& c : per) n_leaf += c.leaf.size();
    leaf.reserve(n_leaf);
    for (const Collector& c : per) {
      leaf.insert(leaf.end(), c.leaf.begin(), c.leaf.end());
      organ.insert(organ.end(), c.organ.begin(), c.organ.end());
      leaf_count.between += c.leaves.between;
      leaf_count.within += c.leaves.within;
    }
    out.counts[1] = leaf_count;
    out.seconds[1] = now_seconds() - t;
    if (req.level == ContactLevel::leaf) {
      out.pairs = std::move(leaf);
      std::sort(out.pairs.begin(), out.pairs.end());
      return out;
    }
    // Each organ pair comes once: an organ is in one cluster, each cluster pair (and each
    // cluster's own pairs) is taken once, and the descent's node pairs split the organ pairs.
    out.counts[2] = count_pairs(organ);
    out.seconds[2] = 0;  // organ pairs come out of the same pass as the leaf level
    if (req.level == ContactLevel::organ) {
      out.pairs = organ;
      std::sort(out.pairs.begin(), out.pairs.end());
      return out;
    }

    // Exact level, over the organ pairs in the order the pass found them: only the pairs that
    // touch are sorted (fewer than half of them on the default stand).
    t = now_seconds();
    std::vector<std::uint8_t>& hit = hit_;
    hit.assign(organ.size(), 0);
    // Every organ's mesh was made with the tree (fit_mbvt, before threads share the library).
    // Each thread's scratch kept from the last detection (its poses' memory warm), its poses
    // forgotten; its pose cache holds two poses (PoseCache::kDetectionSets).
    while (scratch_.size() < static_cast<std::size_t>(threads))
      scratch_.emplace_back(PoseCache::kDetectionSets);
    // The tree's OBBs are the poses' own (make_obb at the stand's transforms) where it was fit with
    // no clearance: the poses take them rather than make them again.
    const Obb* tree_obbs = m.config.clearance == 0 ? m.obbs.data() : nullptr;
    FirstException exact_failed;  // as in the pass above
#pragma omp parallel num_threads(threads)
    {
      ExactScratch& scratch = scratch_[static_cast<std::size_t>(omp_get_thread_num())];
      scratch.poses.forget();
#pragma omp for schedule(dynamic, 64)
      for (std::size_t i = 0; i < organ.size(); ++i) {
        if (exact_failed.caught()) continue;
        try {
          // The records and transforms of the pair twelve on (both lines a 48-byte transform may
          // span): the pass before has pushed them out of the caches, and a pair's first organs
          // are too far apart for the hardware to see a stream. Both organs' lines, twelve pairs
          // ahead: the distance bench_detect measured best.
          if (i + 12 < organ.size())
            for (const std::int32_t id : {organ[i + 12].organ_a, organ[i + 12].organ_b}) {
              const auto k = static_cast<std::size_t>(id);
              __builtin_prefetch(&s.transforms[k]);
              __builtin_prefetch(reinterpret_cast<const char*>(&s.transforms[k]) + 47);
              __builtin_prefetch(&s.organs[k]);
              if (tree_obbs) __builtin_prefetch(&tree_obbs[k]);
            }
          hit[i] = organs_touch(s, lib, organ[i].organ_a, organ[i].organ_b, req.clearance, scratch, tree_obbs)
                       ? 1
                       : 0;
        } catch (...) {
          exact_failed.keep();
        }
      }
    }
    exact_failed.rethrow();
    out.pairs = keep_hits(organ, hit);
    std::sort(out.pairs.begin(), out.pairs.end());
    out.counts[3] = count_pairs(out.pairs);
    out.seconds[3] = now_seconds() - t;
    return out;
  }
};

}  // namespace

std::unique_ptr<DetectionBackend> make_cpu_backend() { return std::make_unique<CpuBackend>(); }

}  // namespace canopy
