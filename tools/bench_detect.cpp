// Detection speed against error on the default stand (Ding et al. 2019 Tables 2-4): per level,
// the time to reach it (bounds built included), its pairs, and false positives against the
// exact level (organ pairs the level could not rule out that do not touch); the AABB-tree
// baseline's build / test / update beside the MBVT's (Table 3); and FCL side by side at the
// exact level, one thread against one thread (its query against canopy's detection with the bounds
// built, and against canopy's query over a built tree, the three taken in turn within each
// repeat; the ratios are the medians of the repeats' ratios). Prints tables, writes CSV.
// Usage: bench_detect [--sizes 200,400,...] [--fcl-max N] [--csv FILE] [--repeats R]
#include "collision/aabb_baseline.hpp"
#include "collision/backend.hpp"
#include "geometry/clock.hpp"
#include "lsystem/grow.hpp"
#include "tools/bench_timing.hpp"
#include "tools/bench_usage.hpp"
#include "tools/detect_options.hpp"
#include "tools/fcl/fcl_reference.hpp"
#include "tools/process_memory.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <numeric>
#include <stdexcept>

using namespace canopy;

namespace {

Stand default_stand(int n) {
  GrowRequest req;
  req.grammar = "grammars/tomato.yaml";
  req.plants = default_stand_layout(n);
  return grow_stand(req);
}

/// Organ pairs a plant- or leaf-level row leaves open: every pair of organs taking part under
/// it, adjacent pairs left out.
std::size_t implied_pairs(const Stand& s, const Mbvt& m, const std::vector<Contact>& rows, bool leaf) {
  std::size_t total = 0;
  std::vector<std::uint32_t> a, b;
  const auto organs_of_plant = [&](std::int32_t p, std::vector<std::uint32_t>& out) {
    out.clear();
    const PlantBound& pb = m.plants[static_cast<std::size_t>(p)];
    for (std::uint32_t c = pb.first_cluster; c < pb.first_cluster + pb.cluster_count; ++c)
      for (std::uint32_t k = m.clusters[c].first; k < m.clusters[c].first + m.clusters[c].count; ++k)
        out.push_back(m.cluster_organs[k]);
  };
  const auto organs_of_cluster = [&](std::int32_t c, std::vector<std::uint32_t>& out) {
    const Cluster& cl = m.clusters[static_cast<std::size_t>(c)];
    out.assign(m.cluster_organs.begin() + cl.first, m.cluster_organs.begin() + cl.first + cl.count);
  };
  for (const Contact& r : rows) {
    if (leaf) organs_of_cluster(r.cluster_a, a), organs_of_cluster(r.cluster_b, b);
    else organs_of_plant(r.plant_a, a), organs_of_plant(r.plant_b, b);
    const bool same = leaf ? r.cluster_a == r.cluster_b : r.plant_a == r.plant_b;
    for (std::size_t i = 0; i < a.size(); ++i)
      for (std::size_t j = same ? i + 1 : 0; j < b.size(); ++j) {
        const auto x = static_cast<std::int32_t>(a[i]), y = static_cast<std::int32_t>(b[j]);
        total += !adjacent(s.organs[a[i]], x, s.organs[b[j]], y);
      }
  }
  return total;
}

}  // namespace

int main(int argc, char** argv) {
  canopy::keep_freed_memory();
  std::vector<int> sizes{200, 400, 600, 800, 1000, 2000, 10000};
  int fcl_max = 1000, repeats = 3;
  std::string csv = "bench/results/detect_cpu.csv";
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) csv = argv[++i];
    else if (!std::strcmp(argv[i], "--fcl-max") && i + 1 < argc) fcl_max = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--repeats") && i + 1 < argc) repeats = std::max(1, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--sizes") && i + 1 < argc) {
      sizes.clear();
      for (char* t = std::strtok(argv[++i], ","); t; t = std::strtok(nullptr, ","))
        sizes.push_back(std::atoi(t));
    } else {
      return help_or_refuse(
          "bench_detect", argv[i],
          "usage: bench_detect [--sizes 200,400,...] [--fcl-max N] [--repeats R] [--csv FILE]\n");
    }
  }
  std::FILE* out = std::fopen(csv.c_str(), "w");
  if (!out) return 1;
  fmt::print(out,
             "plants,organs_per_plant,triangles_per_plant,threads,method,stage,seconds,pairs,false_positives,"
             "missed\n");
  const int all = omp_get_max_threads();
  std::string note;
  auto cpu = cli::make_backend("cpu", note);  // the command line's factory, as `canopy stand --backend cpu`
  fmt::print("{:>6} {:>4} {:<10} {:<14} {:>9} {:>10} {:>12} {:>8}\n", "plants", "thr", "method", "stage",
             "seconds", "pairs", "false pos.", "missed");
  for (int n : sizes) {
    const Stand s = default_stand(n);
    PrototypeLibrary lib;
    std::size_t tris = 0;
    for (const OrganRecord& r : s.organs) tris += lib.get(r).triangle_count();
    const double opp = static_cast<double>(s.organ_count()) / n, tpp = static_cast<double>(tris) / n;
    // The exact answer and the implied pairs of each level (one thread, outside the timings).
    DetectRequest req;
    const std::vector<Contact> exact = cpu->detect(s, req).pairs;
    const Mbvt m = build_mbvt(s, lib, MbvtConfig{});
    std::array<std::size_t, 4> pairs{}, fp{};
    for (ContactLevel level : {ContactLevel::plant, ContactLevel::leaf, ContactLevel::organ}) {
      req.level = level;
      const auto rows = cpu->detect(s, req).pairs;
      const auto l = static_cast<std::size_t>(level);
      pairs[l] = rows.size();
      fp[l] = (level == ContactLevel::organ ? rows.size()
                                            : implied_pairs(s, m, rows, level == ContactLevel::leaf)) -
              exact.size();
    }
    pairs[3] = exact.size();
    for (int threads : thread_counts(all)) {
      omp_set_num_threads(threads);
      const auto row = [&](const char* method, const std::string& stage, double sec, std::size_t p,
                           long long f, long long missed) {
        fmt::print("{:>6} {:>4} {:<10} {:<14} {:>9.4f} {:>10} {:>12} {:>8}\n", n, threads, method, stage, sec,
                   p, f, missed);
        fmt::print(out, "{},{:.1f},{:.0f},{},{},{},{:.6f},{},{},{}\n", n, opp, tpp, threads, method, stage,
                   sec, p, f, missed);
      };
      for (ContactLevel level :
           {ContactLevel::plant, ContactLevel::leaf, ContactLevel::organ, ContactLevel::exact}) {
        DetectRequest r;
        r.level = level;
        r.threads = threads;
        const double t = median_time(repeats, [&] { cpu->detect(s, r); });
        const auto l = static_cast<std::size_t>(level);
        row("mbvt", std::string("to ") + std::string(name_of(level)), t, pairs[l],
            static_cast<long long>(fp[l]), 0);
      }
      // The query alone (the paper's "test" phase, what FCL's query time is): the tree built once,
      // then detection to the exact level over it (a re-detection with no organ moved refits
      // nothing). Its pairs must be the exact level's.
      {
        DetectRequest r;
        r.threads = threads;
        cpu->detect(s, r);
        std::vector<Contact> again;
        const double t = median_time(repeats, [&] { again = cpu->redetect(s, r, {}).pairs; });
        if (again != exact)
          throw std::runtime_error("bench_detect: the query over a built tree gave other pairs");
        row("mbvt", "query(exact)", t, again.size(), 0, 0);
      }
      // Table 3: build, test (organ level), update.
      // Built as the backend builds it: anew in place, the arrays' memory kept from the last build.
      Mbvt mb;
      const double build = median_time(repeats, [&] { rebuild_mbvt(mb, s, lib, MbvtConfig{}); });
      std::vector<std::uint32_t> everything(s.organ_count());
      std::iota(everything.begin(), everything.end(), 0u);
      const double refit = median_time(repeats, [&] { refit_mbvt(mb, s, lib, everything); });
      row("mbvt", "build", build, 0, -1, -1);
      row("mbvt", "update(refit)", refit, 0, -1, -1);
      AabbTree tree;
      const double abuild = median_time(repeats, [&] { tree.build(s, lib, default_collide_kinds()); });
      std::vector<Contact> boxes;
      const double atest = median_time(repeats, [&] { boxes = tree.overlapping_pairs(s); });
      row("aabb-tree", "build", abuild, 0, -1, -1);
      row("aabb-tree", "test(organ)", atest, boxes.size(),
          static_cast<long long>(boxes.size() - exact.size()), 0);
      row("aabb-tree", "update(rebuild)", abuild, 0, -1, -1);
    }
    if (n <= fcl_max) {
      const FclScene fcl(s, lib, default_collide_kinds());
      // FCL's query and canopy's detection (its bounds built, then over the built tree alone),
      // one thread each, taken in turn within every repeat (the order swapped from repeat to
      // repeat), so that the two see the same stretch of this machine's speed; the ratios are
      // the medians of the repeats' own ratios.
      DetectRequest r;
      r.threads = 1;
      omp_set_num_threads(1);  // the tree's build too
      std::vector<std::pair<int, int>> theirs;
      std::vector<double> f_s, built_s, query_s, built_ratio, query_ratio;
      for (int k = 0; k < repeats; ++k) {
        double f = 0, built = 0, query = 0;
        const auto time_fcl = [&] {
          const auto t0 = std::chrono::steady_clock::now();
          auto pairs = fcl.query();
          f = seconds_since(t0);
          if (k > 0 && pairs != theirs)
            throw std::runtime_error("bench_detect: FCL's query gave different pairs on a repeat");
          theirs = std::move(pairs);
        };
        const auto time_ours = [&] {
          auto t0 = std::chrono::steady_clock::now();
          const bool same_built = cpu->detect(s, r).pairs == exact;
          built = seconds_since(t0);
          t0 = std::chrono::steady_clock::now();
          const bool same_query = cpu->redetect(s, r, {}).pairs == exact;
          query = seconds_since(t0);
          if (!same_built || !same_query)
            throw std::runtime_error("bench_detect: canopy's pairs changed beside FCL's");
        };
        if (k % 2) time_fcl(), time_ours();
        else time_ours(), time_fcl();
        f_s.push_back(f), built_s.push_back(built), query_s.push_back(query);
        built_ratio.push_back(f / built), query_ratio.push_back(f / query);
      }
      omp_set_num_threads(all);
      std::vector<std::pair<int, int>> ours;
      for (const Contact& c : exact) ours.emplace_back(c.organ_a, c.organ_b);
      std::vector<std::pair<int, int>> only_ours, only_fcl;
      std::set_difference(ours.begin(), ours.end(), theirs.begin(), theirs.end(),
                          std::back_inserter(only_ours));
      std::set_difference(theirs.begin(), theirs.end(), ours.begin(), ours.end(),
                          std::back_inserter(only_fcl));
      const double f_med = median(f_s), built_med = median(built_s), query_med = median(query_s);
      fmt::print("{:>6} {:>4} {:<10} {:<14} {:>9.4f} {:>10}   build {:.3f} s; only canopy {}, only FCL {}\n",
                 n, 1, "fcl", "to exact", f_med, theirs.size(), fcl.build_s(), only_ours.size(),
                 only_fcl.size());
      fmt::print("{:>6} {:>4} {:<10} {:<14} {:>9.4f} {:>10}   beside FCL's: bounds built {:.4f} s\n", n, 1,
                 "mbvt", "query(beside)", query_med, exact.size(), built_med);
      fmt::print(
          "{:>6} {:>4} {:<10} FCL's query / canopy's, one thread, taken in turn: {:.2f}x (canopy's bounds "
          "built included), "
          "{:.2f}x (query against query); medians of {} repeats' ratios\n",
          n, 1, "ratio", median(built_ratio), median(query_ratio), repeats);
      fmt::print(out, "{},{:.1f},{:.0f},1,fcl,build,{:.6f},0,-1,-1\n", n, opp, tpp, fcl.build_s());
      fmt::print(out, "{},{:.1f},{:.0f},1,fcl,to exact,{:.6f},{},{},{}\n", n, opp, tpp, f_med, theirs.size(),
                 only_fcl.size(), only_ours.size());
      fmt::print(out, "{},{:.1f},{:.0f},1,mbvt,to exact(beside fcl),{:.6f},{},0,0\n", n, opp, tpp, built_med,
                 exact.size());
      fmt::print(out, "{},{:.1f},{:.0f},1,mbvt,query(beside fcl),{:.6f},{},0,0\n", n, opp, tpp, query_med,
                 exact.size());
    }
  }
  std::fclose(out);
  fmt::print("wrote {}\n", csv);
  return 0;
}
