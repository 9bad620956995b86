// Resolution quality against speed: for the default stand (and denser spacings), contacts
// before, rounds, time, mean and max turn, and residual contacts by a fresh exact detection
// afterwards, with detection at the exact level and at the organ level (faster per round, but it
// turns organs whose boxes met without touching: organs_moved shows how many more), on the CPU
// and, in a CUDA build on a machine with a GPU, on the GPU. Prints a table, writes CSV.
// Usage: bench_resolve [--sizes 100,1000,10000] [--dense-sizes 100,1000] [--backends cpu,cuda,auto]
//                      [--levels exact,organ] [--threads T] [--candidates N] [--axes N] [--step DEG]
//                      [--csv FILE] [--append] [--host-search] [--lanes N] [--batch N] [--host-runner]
//        (`--help` says what the last four do)
#include "resolution/attempt_runner_host.hpp"
#include "resolution/resolve.hpp"
#include "geometry/clock.hpp"
#include "geometry/split_list.hpp"
#include "lsystem/grow.hpp"
#include "tools/bench_timing.hpp"
#include "tools/bench_usage.hpp"
#include "tools/detect_options.hpp"
#include "tools/heap_pages.hpp"
#include "tools/process_rerun.hpp"
#include "tools/process_memory.hpp"
#include "tools/resolve_stats.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

using namespace canopy;

namespace {

/// A comma-separated option's items, empty ones skipped.
std::vector<std::string> items(const char* s) {
  std::vector<std::string> v = split_list(s);
  std::erase(v, std::string());
  return v;
}

struct Spacing {
  std::string name;
  double plant, row;
};

}  // namespace

int main(int argc, char** argv) {
  try {
    canopy::rerun_for_run(canopy::heap_pages_for(canopy::command_runs_on_gpu(argc, argv, "cpu")), true, argv);
  } catch (const std::invalid_argument& e) {  // the environment's heap-page choice, misspelt
    std::fprintf(stderr, "bench_resolve: error: %s\n", e.what());
    return 2;
  }
  canopy::keep_freed_memory();
  std::vector<int> sizes{100, 1000, 10000}, dense_sizes{100, 1000};
  std::vector<std::string> backends{"cpu"}, levels{"exact", "organ"};
  int threads = 0;
  bool append = false, device_search = true, host_runner = false, stats = false;
  std::size_t lanes = ResolveRequest{}.bulk_lanes, batch = ResolveRequest{}.batch_contacts,
              host_below = ResolveRequest{}.host_levels_below;
  ResolveConfig base;
  std::string csv = "bench/results/resolve.csv";
  for (int i = 1; i < argc; ++i) {
    const auto ints = [&](std::vector<int>& v) {
      v.clear();
      for (const std::string& x : items(argv[++i])) v.push_back(std::stoi(x));
    };
    if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) csv = argv[++i];
    else if (!std::strcmp(argv[i], "--sizes") && i + 1 < argc) ints(sizes);
    else if (!std::strcmp(argv[i], "--dense-sizes") && i + 1 < argc) ints(dense_sizes);
    else if (!std::strcmp(argv[i], "--backends") && i + 1 < argc) backends = items(argv[++i]);
    else if (!std::strcmp(argv[i], "--levels") && i + 1 < argc) levels = items(argv[++i]);
    else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) threads = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--candidates") && i + 1 < argc) base.candidates = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--axes") && i + 1 < argc) base.axis_fan = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--step") && i + 1 < argc) base.scan_step_deg = std::atof(argv[++i]);
    else if (!std::strcmp(argv[i], "--append")) append = true;
    else if (!std::strcmp(argv[i], "--device-search")) device_search = true;  // the default
    else if (!std::strcmp(argv[i], "--host-search")) device_search = false;
    else if (!std::strcmp(argv[i], "--host-runner")) host_runner = true;
    else if (!std::strcmp(argv[i], "--resolve-stats")) stats = true;
    else if (!std::strcmp(argv[i], "--lanes") && i + 1 < argc)
      lanes = static_cast<std::size_t>(std::max(1, std::atoi(argv[++i])));
    else if (!std::strcmp(argv[i], "--batch") && i + 1 < argc)
      batch = static_cast<std::size_t>(std::max(1, std::atoi(argv[++i])));
    else if (!std::strcmp(argv[i], "--host-below") && i + 1 < argc)
      host_below = static_cast<std::size_t>(std::max(0, std::atoi(argv[++i])));
    else {
      return help_or_refuse(
          "bench_resolve", argv[i],
          fmt::format("usage: bench_resolve [--sizes 100,1000,10000] [--dense-sizes 100,1000] [--backends "
                      "cpu,cuda,auto]\n"
                      "       [--levels exact,organ] [--threads T] [--candidates N] [--axes N] [--step DEG] "
                      "[--csv FILE] [--append]\n"
                      "       [--host-search]     (CUDA: the host's candidate-by-candidate search instead of "
                      "each level's\n"
                      "                            attempts on the device, the default)\n"
                      "       [--lanes N]         (attempts on the device: batches of contacts planned at "
                      "once, default {})\n"
                      "       [--batch N]         (contacts per batch of planning at most, default {})\n"
                      "       [--host-below N]    (attempts on the device: levels of fewer candidates "
                      "searched on the host,\n"
                      "                            default {}; 0: every level on the device)\n"
                      "       [--host-runner]     (the CPU backend plans as the device does, level by level "
                      "in lanes,\n"
                      "                            with the host answering the attempts: the device path's "
                      "host side\n"
                      "                            where there is no GPU, for profiling; the same turns)\n"
                      "       [--resolve-stats]   (each resolution's statistics on stderr, as canopy stand "
                      "--resolve-stats)\n"
                      "The heap is in large pages when --backends names cuda, else small "
                      "(CANOPY_HEAP_PAGES=large|small\n"
                      "overrides; tools/heap_pages.hpp); the CSV's config column says which.\n",
                      ResolveRequest{}.bulk_lanes, ResolveRequest{}.batch_contacts,
                      ResolveRequest{}.host_levels_below));
    }
  }
  std::FILE* out = std::fopen(csv.c_str(), append ? "a" : "w");
  if (!out) return 1;
  const std::string config =
      fmt::format("candidates={} axes={} step={} heap={} host_below={}", base.candidates, base.axis_fan,
                  base.scan_step_deg, heap_pages_in_use(), host_below);
  if (!append)
    fmt::print(
        out,
        "config,threads,backend,device,spacing,plant_spacing_m,row_spacing_m,plants,organs_per_plant,level,"
        "contacts_before_exact,"
        "contacts_before_level,rounds,organs_moved,organs_carried,mean_turn_deg,max_turn_deg,residual_exact,"
        "residual_level,detect_s,resolve_s,plan_s,redetect_s\n");
  fmt::print("{:<5} {:<8} {:>6} {:<6} {:>9} {:>7} {:>8} {:>7} {:>7} {:>9} {:>9} {:>9} {:>7}\n", "back",
             "spacing", "plants", "level", "before", "rounds", "turned", "mean°", "max°", "residual",
             "detect s", "resolve s", "plan s");
  const std::vector<Spacing> spacings{{"default", 0.4, 1.0}, {"dense", 0.25, 0.6}};
  for (const std::string& bname : backends) {
    // From the command line's factory: cpu, cuda or auto as `canopy stand --backend` gets them.
    std::unique_ptr<DetectionBackend> backend;
    std::string note;
    try {
      backend = cli::make_backend(bname, note);
    } catch (const std::invalid_argument& e) {
      fmt::print("backend {}: not available here, skipped ({})\n", bname, e.what());
      continue;
    }
    fmt::print("backend {}: {}\n", bname, note);
    for (const Spacing& sp : spacings)
      for (int n : sp.name == "default" ? sizes : dense_sizes)
        for (const std::string& lname : levels) {
          GrowRequest g;
          g.grammar = "grammars/tomato.yaml";
          g.plants = default_stand_layout(n);
          for (PlantPlacement& p : g.plants) p.x *= sp.plant / 0.4, p.y *= sp.row / 1.0;
          g.threads = threads;
          Stand s = grow_stand(g);
          ResolveRequest req;
          req.detect.threads = threads;
          req.config = base;
          req.bulk_attempts = device_search;
          PrototypeLibrary runner_lib;
          HostAttemptRunner runner(runner_lib, threads > 0 ? threads : omp_get_max_threads(), lanes);
          if (host_runner && bname == "cpu") req.attempts = &runner;
          req.bulk_lanes = lanes;
          req.batch_contacts = batch;
          req.host_levels_below = host_below;
          req.statistics = stats;
          req.config.level = *parse_contact_level(lname);
          auto fresh = make_cpu_backend();  // the independent counts before and after
          const std::size_t before_exact = fresh->detect(s, DetectRequest{}).pairs.size();
          DetectRequest at = req.detect;
          at.level = req.config.level;
          auto t = std::chrono::steady_clock::now();
          const Contacts first = backend->detect(s, at);
          const double detect_s = seconds_since(t);
          t = std::chrono::steady_clock::now();
          const ResolveResult r = resolve(s, *backend, req, first);
          const double resolve_s = seconds_since(t);
          if (stats) fmt::print(stderr, "{}", cli::resolve_stats_text(r.stats));
          double plan = 0, redetect = 0;
          for (const ResolveRound& x : r.per_round) plan += x.plan_s, redetect += x.detect_s;
          const std::size_t residual = fresh->detect(s, DetectRequest{}).pairs.size();
          fmt::print(
              "{:<5} {:<8} {:>6} {:<6} {:>9} {:>7} {:>8} {:>7.2f} {:>7.2f} {:>9} {:>9.3f} {:>9.3f} "
              "{:>7.3f}\n",
              bname, sp.name, n, lname, before_exact, r.rounds, r.organs_moved, r.mean_turn_deg,
              r.max_turn_deg, residual, detect_s, resolve_s, plan);
          // How the rounds were planned, as they ran (nothing added for the CPU backend's host search).
          const std::string planned =
              r.search == "device" ? fmt::format(" device-search lanes={} batch={}", r.lanes, batch)
              : r.search == "host" && backend->name() == "cpu" ? std::string()
                                                               : fmt::format(" {}-search", r.search);
          fmt::print(out, "{}{},{},", config, planned, threads);
          fmt::print(
              out,
              "{},{},{},{},{},{},{:.1f},{},{},{},{},{},{},{:.4f},{:.4f},{},{},{:.6f},{:.6f},{:.6f},{:.6f}\n",
              backend->name(), backend->device(), sp.name, sp.plant, sp.row, n,
              static_cast<double>(s.organ_count()) / n, lname, before_exact, first.pairs.size(), r.rounds,
              r.organs_moved, r.organs_carried, r.mean_turn_deg, r.max_turn_deg, residual, r.contacts_after,
              detect_s, resolve_s, plan, redetect);
          std::fflush(out);
        }
  }
  std::fclose(out);
  fmt::print("wrote {}\n", csv);
  return 0;
}
