// Generation and export speed: grow (derive + interpret + turtle + place), layout, and each
// export format, for default stands of N plants, on one thread and on all; the disk's own write
// speed measured the same way (buffered writes of a 1 GiB file, closed). Prints a table, writes CSV.
// Usage: bench_generate [--sizes 100,1000,10000] [--grammar FILE] [--csv FILE] [--dir DIR] [--no-export]
#include "geometry/clock.hpp"
#include "geometry/export.hpp"
#include "geometry/layout.hpp"
#include "lsystem/grow.hpp"
#include "tools/bench_timing.hpp"
#include "tools/bench_usage.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <vector>
#include <unistd.h>

using namespace canopy;
namespace fs = std::filesystem;

namespace {

/// Writes `bytes` to a file in 1 MiB blocks, buffered like the exports, optionally synced.
double disk_write_mb_s(const std::string& dir, bool sync, std::size_t bytes = std::size_t(1) << 30) {
  std::vector<char> block(1 << 20, 'x');
  const std::string path = dir + "/disk-speed.bin";
  const auto t = std::chrono::steady_clock::now();
  std::FILE* f = std::fopen(path.c_str(), "wb");
  for (std::size_t w = 0; w < bytes; w += block.size()) std::fwrite(block.data(), 1, block.size(), f);
  std::fflush(f);
  if (sync) fdatasync(fileno(f));
  std::fclose(f);
  const double s = seconds_since(t);
  fs::remove(path);
  return static_cast<double>(bytes) / 1e6 / s;
}

}  // namespace

int main(int argc, char** argv) {
  std::string grammar = "grammars/tomato.yaml", csv = "bench/results/generate.csv",
              dir = "/tmp/canopy-bench-generate";
  std::vector<int> sizes{100, 1000, 10000};
  bool with_export = true;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) csv = argv[++i];
    else if (!std::strcmp(argv[i], "--dir") && i + 1 < argc) dir = argv[++i];
    else if (!std::strcmp(argv[i], "--grammar") && i + 1 < argc) grammar = argv[++i];
    else if (!std::strcmp(argv[i], "--no-export")) with_export = false;
    else if (!std::strcmp(argv[i], "--sizes") && i + 1 < argc) {
      sizes.clear();
      for (char* t = std::strtok(argv[++i], ","); t; t = std::strtok(nullptr, ","))
        sizes.push_back(std::atoi(t));
    } else {
      return help_or_refuse("bench_generate", argv[i],
                            "usage: bench_generate [--sizes 100,1000,10000] [--grammar FILE] [--csv FILE] "
                            "[--dir DIR] [--no-export]\n");
    }
  }
  fs::create_directories(dir);
  // The disk's write speed two ways, for the record: into the page cache and through to the
  // device (fdatasync). Each export row is compared with a same-size write made right after it.
  const double cached = disk_write_mb_s(dir, false);
  const double disk = disk_write_mb_s(dir, true);
  const int all = omp_get_max_threads();
  std::FILE* out = std::fopen(csv.c_str(), "w");
  if (!out) return 1;
  fmt::print(out,
             "plants,threads,stage,seconds,organs,triangles,bytes,organs_per_s,triangles_per_s,mb_per_s,disk_"
             "mb_per_s\n");
  fmt::print("disk write speed, 1 GiB: {:.0f} MB/s into the page cache, {:.0f} MB/s synced to the device\n",
             cached, disk);
  fmt::print("{:>7} {:>7} {:<17} {:>9} {:>10} {:>11} {:>12} {:>13} {:>9} {:>9}\n", "plants", "threads",
             "stage", "seconds", "organs", "triangles", "Morgans/s", "Mtriangles/s", "MB/s", "disk MB/s");
  for (int n : sizes) {
    for (int threads : thread_counts(all)) {
      omp_set_num_threads(threads);
      double disk_now = 0;
      const auto row = [&](const char* stage, double s, std::size_t organs, std::size_t tris,
                           std::size_t bytes) {
        fmt::print("{:>7} {:>7} {:<17} {:>9.3f} {:>10} {:>11} {:>12.2f} {:>13.1f} {:>9.0f} {:>9.0f}\n", n,
                   threads, stage, s, organs, tris, organs / s / 1e6, tris / s / 1e6, bytes / s / 1e6,
                   bytes ? disk_now : 0.0);
        fmt::print(out, "{},{},{},{:.6f},{},{},{},{:.0f},{:.0f},{:.1f},{:.0f}\n", n, threads, stage, s,
                   organs, tris, bytes, organs / s, tris / s, bytes / s / 1e6, bytes ? disk_now : 0.0);
      };
      auto t = std::chrono::steady_clock::now();
      GrowRequest req;
      req.grammar = grammar;
      req.plants = default_stand_layout(n);
      const double layout_s = seconds_since(t);
      req.threads = threads;
      t = std::chrono::steady_clock::now();
      const Stand stand = grow_stand(req);
      const double grow_s = seconds_since(t);
      PrototypeLibrary lib;
      std::size_t tris = 0;
      for (const OrganRecord& r : stand.organs) tris += lib.get(r).triangle_count();
      row("layout", layout_s, stand.organ_count(), 0, 0);
      row("grow", grow_s, stand.organ_count(), tris, 0);
      if (!with_export) continue;
      for (const char* fmt_name : {"glb", "ply", "organs.csv"}) {
        if (n > 1000 && threads == 1 && std::strcmp(fmt_name, "organs.csv") != 0)
          continue;  // keep the run short
        const std::string name =
            std::strcmp(fmt_name, "organs.csv") == 0 ? "organs.csv" : std::string("stand.") + fmt_name;
        // First the work alone, into /dev/null: what the exporter can do when the disk keeps up.
        t = std::chrono::steady_clock::now();
        {
          AtomicFile f("/dev/null", AtomicFile::Direct{});
          if (name == "stand.glb") write_glb(stand, lib, f);
          else if (name == "stand.ply") write_ply(stand, lib, f);
          else write_organs_csv(stand, lib, f);
          f.close();
        }
        const double compute_s = seconds_since(t);
        t = std::chrono::steady_clock::now();
        {
          // Written in place, as before files were synced: the disk row below is not synced either.
          AtomicFile f(dir + "/" + name, AtomicFile::Direct{});
          if (name == "stand.glb") write_glb(stand, lib, f);
          else if (name == "stand.ply") write_ply(stand, lib, f);
          else write_organs_csv(stand, lib, f);
          f.close();
        }
        const double s = seconds_since(t);
        const std::size_t bytes = fs::file_size(dir + "/" + name);
        fs::remove(dir + "/" + name);
        // The disk measured the same way right after, with a file of the same size: large files
        // outrun the page cache and go at the device's own speed.
        disk_now = disk_write_mb_s(dir, false, bytes);
        row((std::string(fmt_name) + " (null)").c_str(), compute_s, stand.organ_count(), tris, bytes);
        row(fmt_name, s, stand.organ_count(), tris, bytes);
      }
    }
  }
  std::fclose(out);
  fmt::print("wrote {}\n", csv);
  return 0;
}
