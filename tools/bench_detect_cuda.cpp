// GPU detection against the CPU on the default stand (Ding et al. 2019 Table 4, then on to
// 100,000 plants): per level, medians over repeats (after a warm-up) of
//   load    the tree's shape made on the host and the stand uploaded (once per stand),
//   fit     every box fitted on the device,
//   stages  plant grid to final list, host wall clock (launches, syncs, the list downloaded),
//   kernel  the kernels alone (CUDA events),
//   detect  fit + stages by the host wall clock: detection of a stand resident on the device,
//   again   redetect() with nothing moved (stages alone, as a resolution round without refit),
// pairs, false positives against the exact level, the CPU backend's time on the same stand, and
// the device name. Prints a table, writes CSV.
// Usage: bench_detect_cuda [--sizes 2000,4000,...] [--repeats R] [--csv FILE]
#include "collision/backend.hpp"
#include "geometry/clock.hpp"
#include "lsystem/grow.hpp"
#include "tools/bench_timing.hpp"
#include "tools/bench_usage.hpp"
#include "tools/detect_options.hpp"
#include "tools/process_memory.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstring>

using namespace canopy;

int main(int argc, char** argv) {
  canopy::keep_freed_memory();
  std::vector<int> sizes{2000, 4000, 6000, 8000, 10000, 100000};
  int repeats = 5;
  std::string csv = "bench/results/detect_cuda.csv";
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) csv = argv[++i];
    else if (!std::strcmp(argv[i], "--repeats") && i + 1 < argc) repeats = std::max(1, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--sizes") && i + 1 < argc) {
      sizes.clear();
      for (char* t = std::strtok(argv[++i], ","); t; t = std::strtok(nullptr, ","))
        sizes.push_back(std::atoi(t));
    } else {
      return help_or_refuse("bench_detect_cuda", argv[i],
                            "usage: bench_detect_cuda [--sizes 2000,4000,...] [--repeats R] [--csv FILE]\n");
    }
  }
  // From the command line's factory, as `canopy stand --backend cuda` and `--backend cpu` get them.
  std::string note;
  auto gpu = cli::make_backend("cuda", note);
  auto cpu = cli::make_backend("cpu", note);
  std::FILE* out = std::fopen(csv.c_str(), "w");
  if (!out) return 1;
  fmt::print(
      out,
      "device,plants,organs_per_plant,triangles_per_plant,level,gpu_load_s,gpu_fit_s,gpu_stage_s,gpu_kernel_"
      "s,"
      "gpu_detect_s,gpu_again_s,cpu_total_s,pairs,false_positives_vs_exact,"
      "again_plant_s,again_leaf_s,again_organ_s,again_exact_s,again_plant_kernel_s,again_leaf_kernel_s,"
      "again_organ_kernel_s,again_exact_kernel_s\n");
  fmt::print("device: {}\n{:>7} {:<6} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>10}\n",
             gpu->device(), "plants", "level", "load s", "fit s", "stage s", "kernel s", "detect s",
             "again s", "cpu s", "pairs", "organ FP");
  for (int n : sizes) {
    GrowRequest req;
    req.grammar = "grammars/tomato.yaml";
    req.plants = default_stand_layout(n);
    const Stand s = grow_stand(req);
    PrototypeLibrary lib;
    std::size_t tris = 0;
    for (const OrganRecord& r : s.organs) tris += lib.get(r).triangle_count();
    std::size_t exact_pairs = 0;
    for (ContactLevel level :
         {ContactLevel::exact, ContactLevel::organ, ContactLevel::leaf, ContactLevel::plant}) {
      DetectRequest dr;
      dr.level = level;
      gpu->detect(s, dr);  // warm-up
      std::vector<double> load, fit, stage, kernel, detect, again, cpu_total;
      std::array<std::vector<double>, 4> level_s, level_kernel_s;  // per level, in the redetect
      Contacts c;
      for (int r = 0; r < repeats; ++r) {
        auto t = std::chrono::steady_clock::now();
        c = gpu->detect(s, dr);
        detect.push_back(seconds_since(t) - c.load_s);
        load.push_back(c.load_s);
        fit.push_back(c.build_s);
        double st = 0;
        for (double x : c.seconds) st += x;
        stage.push_back(st);
        double k = 0;
        for (double x : c.device_seconds) k += x;
        kernel.push_back(k);
        t = std::chrono::steady_clock::now();
        const Contacts d = gpu->redetect(s, dr, {});
        again.push_back(seconds_since(t));
        for (std::size_t l = 0; l < 4; ++l)
          level_s[l].push_back(d.seconds[l]), level_kernel_s[l].push_back(d.device_seconds[l]);
        if (d.pairs != c.pairs) {
          fmt::print(stderr, "redetect with nothing moved gave another list\n");
          return 1;
        }
      }
      for (int r = 0; r < std::max(1, repeats / 2); ++r) {
        auto t = std::chrono::steady_clock::now();
        cpu->detect(s, dr);
        cpu_total.push_back(seconds_since(t));
      }
      if (level == ContactLevel::exact) exact_pairs = c.pairs.size();
      const long long fp =
          level == ContactLevel::organ ? static_cast<long long>(c.pairs.size() - exact_pairs) : -1;
      fmt::print("{:>7} {:<6} {:>9.4f} {:>9.5f} {:>9.5f} {:>9.5f} {:>9.5f} {:>9.5f} {:>9.4f} {:>9} {:>10}\n",
                 n, name_of(level), median(load), median(fit), median(stage), median(kernel), median(detect),
                 median(again), median(cpu_total), c.pairs.size(), fp);
      fmt::print(out, "{},{},{:.1f},{:.0f},{},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{},{}",
                 gpu->device(), n, static_cast<double>(s.organ_count()) / n, static_cast<double>(tris) / n,
                 name_of(level), median(load), median(fit), median(stage), median(kernel), median(detect),
                 median(again), median(cpu_total), c.pairs.size(), fp);
      for (const auto* v : {&level_s, &level_kernel_s})
        for (const auto& x : *v) fmt::print(out, ",{:.6f}", median(x));
      fmt::print(out, "\n");
    }
  }
  std::fclose(out);
  fmt::print("wrote {}\n", csv);
  return 0;
}
