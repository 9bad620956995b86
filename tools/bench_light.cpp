// canopy light's speed against its error: on the default stand (docs/design.md) of each size, the
// scene's build time and memory, rays per second, and the time for a direct beam plus the sky's
// directions to each standard error asked of the stand's fractions and of each plant's. Prints a
// table, writes CSV (one row per run; bench/run.sh adds commit, date and machine).
// Usage: bench_light [--plants 1000,10000] [--threads T] [--errors 0.01,0.005,0.002,0.001]
//                    [--plant-errors 0.05,0.02] [--sky-directions 46] [--sun 60,180] [--csv FILE] [--append]
#include "geometry/available_memory.hpp"
#include "geometry/clock.hpp"
#include "geometry/layout.hpp"
#include "geometry/split_list.hpp"
#include "geometry/thread_limit.hpp"
#include "light/light.hpp"
#include "lsystem/grow.hpp"
#include "tools/bench_timing.hpp"
#include "tools/bench_usage.hpp"
#include "tools/light_device.hpp"
#include "tools/process_memory.hpp"

#include <fmt/format.h>
#include <omp.h>
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

using namespace canopy;

namespace {

std::vector<double> numbers(const char* s) {
  std::vector<double> v;
  for (const std::string& item : split_list(s)) v.push_back(std::stod(item));
  return v;
}

/// The first line a shell command prints (empty when it fails).
std::string first_line(const std::string& command) {
  std::string out;
  if (std::FILE* p = popen(command.c_str(), "r")) {
    char buf[512];
    if (std::fgets(buf, sizeof buf, p)) out = buf;
    pclose(p);
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

std::string machine() {
  std::ifstream in("/proc/cpuinfo");
  std::string line, model = "unknown CPU";
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) {
      model = line.substr(line.find(':') + 2);
      break;
    }
  char host[256] = {};
  gethostname(host, sizeof host - 1);
  return fmt::format("{} ({} cores, host {})", model, sysconf(_SC_NPROCESSORS_ONLN), host);
}

double resident_mb() { return static_cast<double>(resident_memory()) / (1024.0 * 1024.0); }

double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

}  // namespace

int bench_main(int argc, char** argv) {
  keep_freed_memory();
  std::vector<double> plants{1000, 10000}, errors{0.01, 0.005, 0.002, 0.001}, plant_errors{0.05, 0.02};
  int threads = 0, sky = 46;
  double sun_e = 60, sun_a = 180;
  std::string csv = "bench/results/light.csv";
  std::string grammar = std::string(CANOPY_SOURCE_DIR) + "/grammars/tomato.yaml";
  bool append = false;
  light::Caster caster = light::Caster::automatic;
  std::string backend = "auto";
  for (int i = 1; i < argc; ++i) try {
      if (!std::strcmp(argv[i], "--plants") && i + 1 < argc) plants = numbers(argv[++i]);
      else if (!std::strcmp(argv[i], "--errors") && i + 1 < argc) errors = numbers(argv[++i]);
      else if (!std::strcmp(argv[i], "--plant-errors") && i + 1 < argc) plant_errors = numbers(argv[++i]);
      else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) threads = std::atoi(argv[++i]);
      else if (!std::strcmp(argv[i], "--sky-directions") && i + 1 < argc) sky = std::atoi(argv[++i]);
      else if (!std::strcmp(argv[i], "--sun") && i + 1 < argc) {
        const std::vector<double> s = numbers(argv[++i]);
        if (s.size() != 2) {
          std::fprintf(stderr, "bench_light: --sun takes ELEVATION,AZIMUTH, got %s\n", argv[i]);
          return 2;
        }
        sun_e = s[0], sun_a = s[1];
      } else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) csv = argv[++i];
      else if (!std::strcmp(argv[i], "--grammar") && i + 1 < argc) grammar = argv[++i];
      else if (!std::strcmp(argv[i], "--append")) append = true;
      else if (!std::strcmp(argv[i], "--backend") && i + 1 < argc)
        backend = argv[++i];  // the factory checks it
      else if (!std::strcmp(argv[i], "--caster") && i + 1 < argc) {
        try {
          caster = light::parse_caster(argv[++i]);
        } catch (const std::invalid_argument& e) {
          std::fprintf(stderr, "bench_light: %s\n", e.what());
          return 2;
        }
      } else
        return help_or_refuse(
            "bench_light", argv[i],
            "usage: bench_light [--plants 1000,10000] [--threads T] [--errors 0.01,0.005,0.002,0.001]\n"
            "                   [--plant-errors 0.05,0.02] [--sky-directions 46] [--sun 60,180] [--grammar "
            "FILE] [--csv FILE]\n"
            "                   [--append] [--caster auto|trace|raster] [--backend auto|cpu|cuda]\n"
            "  the default stand of each size; per error: a direct beam and the sky's directions to that "
            "standard\n"
            "  error of the stand's fractions (--errors) or of each plant's, root mean square "
            "(--plant-errors)\n");
    } catch (const std::exception&) {
      std::fprintf(stderr, "bench_light: %s: not a number or list of numbers\n", argv[i]);
      return 2;
    }
  const ThreadLimit thread_limit(threads);
  // Where rasterized passes are drawn: the command line's factory (canopy light --backend).
  std::string device_note;
  std::unique_ptr<light::RasterDevice> device;
  try {
    device = cli::make_light_device(backend, device_note);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_light: %s\n", e.what());
    return 2;
  }
  const int used_threads = omp_get_max_threads();
  const std::string commit =
      first_line(fmt::format("git -C '{}' rev-parse --short HEAD 2>/dev/null", CANOPY_SOURCE_DIR));
  const std::string date = [] {
    const std::time_t t = std::time(nullptr);
    char b[32];
    std::strftime(b, sizeof b, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
    return std::string(b);
  }();
  const std::string where = machine();
  std::string rows;
  const std::string header =
      "plants,organs,organs_per_plant,triangles_per_plant,threads,mode,error_asked,rays,scene_s,trace_s,"
      "total_s,"
      "cpu_s,rays_per_s,scene_mb,bytes_per_organ,ground_cover,ground_cover_se,direct,direct_se,diffuse,"
      "diffuse_se,star,star_se,"
      "plant_se_rms_direct,plant_se_rms_diffuse,caster,raster_device,rays_rasterized,raster_s\n";
  fmt::print("bench_light: {} threads, {}; commit {}; rasterized passes on {}\n", used_threads, where,
             commit.empty() ? "unknown" : commit, device_note);
  fmt::print("{:>7} {:>7} {:>9} {:>10} {:>8} {:>8} {:>8} {:>12} {:>9} {:>9} {:>9} {:>9}\n", "plants", "mode",
             "asked", "rays", "scene s", "trace s", "total s", "rays/s", "direct se", "diff. se", "plant se",
             "star se");
  for (double n_d : plants) {
    const int n = static_cast<int>(n_d);
    GrowRequest req;
    req.grammar = grammar;
    req.plants = default_stand_layout(n);
    const Stand stand = grow_stand(req);
    PrototypeLibrary lib;
    std::size_t triangles = 0;
    for (const OrganRecord& r : stand.organs) triangles += lib.get(r).triangle_count();
    // The scene alone: its build time and the memory it holds.
    const double mb0 = resident_mb();
    double scene_mb = 0;
    {
      light::Scene scene(stand, lib);
      scene.build();
      scene_mb = resident_mb() - mb0;
    }
    const int rows_n = n < 100 ? 1 : (n + 99) / 100, per_row = n < 100 ? n : 100;
    light::LightConfig base;
    base.suns = {{sun_e, sun_a}};
    base.sky_directions = sky;
    base.caster = caster;
    base.device = device.get();
    base.tile = {-0.2, -0.5, (per_row - 0.5) * 0.4, rows_n - 0.5};
    const auto run = [&](const std::string& mode, double asked, light::LightConfig c) {
      const double cpu0 = cpu_seconds();
      const auto t0 = std::chrono::steady_clock::now();
      const light::LightResult r = light::compute_light(stand, lib, c);
      const double total = seconds_since(t0), cpu = cpu_seconds() - cpu0;
      const auto rms = [](const std::vector<light::Estimate>& v) {
        double s = 0;
        for (const auto& e : v) s += e.se * e.se;
        return v.empty() ? 0.0 : std::sqrt(s / static_cast<double>(v.size()));
      };
      const double diff = r.diffuse ? r.diffuse->fraction.value : NAN,
                   diff_se = r.diffuse ? r.diffuse->fraction.se : NAN;
      const double star = r.diffuse ? r.diffuse->star.value : NAN,
                   star_se = r.diffuse ? r.diffuse->star.se : NAN;
      const double prms_diff = r.diffuse ? rms(r.diffuse->plant) : NAN;
      fmt::print(
          "{:>7} {:>7} {:>9.6g} {:>10} {:>8.3f} {:>8.3f} {:>8.3f} {:>12.0f} {:>9.5f} {:>9.5f} {:>9.5f} "
          "{:>9.5f}\n",
          n, mode, asked, r.rays, r.scene_s, r.trace_s, total, static_cast<double>(r.rays) / r.trace_s,
          r.direct.empty() ? NAN : r.direct[0].fraction.se, diff_se,
          r.direct.empty() ? NAN : rms(r.direct[0].plant), star_se);
      rows += fmt::format(
          "{},{},{:.1f},{:.0f},{},{},{:.6g},{},{:.4f},{:.4f},{:.4f},{:.4f},{:.0f},{:.1f},{:.0f},{:.6f},{:.6f}"
          ",{:."
          "6f},{:.6f},{:.6f},{:"
          ".6f},{:.6f},{:.6f},{:.6f},{:.6f},{},{},{},{:.4f}\n",
          n, stand.organ_count(), static_cast<double>(stand.organ_count()) / n,
          static_cast<double>(triangles) / n, used_threads, mode, asked, r.rays, r.scene_s, r.trace_s, total,
          cpu, static_cast<double>(r.rays) / r.trace_s, scene_mb,
          scene_mb * 1048576.0 / static_cast<double>(stand.organ_count()), r.ground.fraction.value,
          r.ground.fraction.se, r.direct.empty() ? NAN : r.direct[0].fraction.value,
          r.direct.empty() ? NAN : r.direct[0].fraction.se, diff, diff_se, star, star_se,
          r.direct.empty() ? NAN : rms(r.direct[0].plant), prms_diff, light::caster_name(caster),
          r.raster_passes ? r.raster_device : std::string("none"), r.raster_rays, r.raster_s);
    };
    // Rays per second: the direct beam alone at a fixed density (about 2 million rays).
    {
      light::LightConfig c = base;
      c.sky_directions = 0;
      c.rays_per_m2 = 2e6 / base.tile.area();
      run("rays", *c.rays_per_m2, c);
    }
    for (double e : errors) {
      light::LightConfig c = base;
      c.error = e;
      run("stand", e, c);
    }
    for (double e : plant_errors) {
      light::LightConfig c = base;
      c.plant_error = e;
      run("plant", e, c);
    }
  }
  const bool exists = std::ifstream(csv).good();
  std::FILE* f = std::fopen(csv.c_str(), append ? "a" : "w");
  if (!f) {
    std::fprintf(stderr, "bench_light: cannot write %s\n", csv.c_str());
    return 1;
  }
  if (!append || !exists) std::fputs(header.c_str(), f);
  std::fputs(rows.c_str(), f);
  std::fclose(f);
  fmt::print("wrote {}\n", csv);
  return 0;
}

int main(int argc, char** argv) {
  try {
    return bench_main(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_light: error: %s\n", e.what());
    return 1;
  }
}
