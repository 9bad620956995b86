// `canopy stand` as users run it, stage by stage. Each size runs in a process of its own (this
// program started again, as a user starts canopy), which calls run_stand (tools/stand_run.cpp,
// canopy stand's own code) with canopy stand's defaults on the default stand (docs/design.md): rows of
// 100 plants 1.0 m apart, 0.4 m between plants, random rotation, 0.02 m jitter, seed 1, resolved,
// `stand.glb` written (`stand.ply` above 10,000 plants, where a glb would pass the format's
// 4 GiB). The stage times are the run's own (report.json's timings_s and StandOutcome); this
// program adds what only the parent sees: the process's start (spawn to main, a heap-page rerun
// included), its end (after the run until the process is gone), peak RSS and CPU time, and the
// write speed of the disk the files go to, measured in the same run.
// Usage: bench_stand [--sizes 1000,10000,100000] [--backend cpu|cuda|auto] [--formats F] [--glb-compact]
//                    [--threads T] [--steps N] [--grammar FILE] [--dir DIR] [--disk-mb MB] [--csv FILE]
//                    [--append]
#include "tools/bench_usage.hpp"
#include "tools/disk_speed.hpp"
#include "tools/heap_pages.hpp"
#include "tools/process_rerun.hpp"
#include "tools/process_end.hpp"
#include "tools/process_memory.hpp"
#include "tools/stand_run.hpp"
#ifdef CANOPY_HAVE_CUDA
#include "cuda/device_buffer.hpp"
#endif

#include <fmt/format.h>
#include <omp.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

extern char** environ;

using namespace canopy;
namespace fs = std::filesystem;

namespace {

const char* kUsage =
    "usage: bench_stand [--sizes 1000,10000,100000] [--backend cpu|cuda|auto] [--formats F] [--glb-compact]\n"
    "                   [--threads T] [--steps N] [--grammar FILE] [--dir DIR] [--disk-mb MB] [--csv FILE] "
    "[--append]\n"
    "Runs canopy stand's pipeline (run_stand, canopy stand's defaults) on the default stand of each size, "
    "each in a\n"
    "process of its own, and prints and writes (CSV, default bench/results/stand.csv) its stages: start-up, "
    "growth,\n"
    "tree build, upload, detection, resolution, detection after, export formatting and writing, commit, the "
    "end,\n"
    "peak RSS, device memory and the export's speed as a fraction of the disk's (measured first: --disk-mb "
    "MB\n"
    "written and synced in DIR). Sizes: below 100 one row, else multiples of 100. --formats: default glb up "
    "to\n"
    "10,000 plants, ply above. --backend: default auto. --dir: default a new folder under the system's "
    "temporary one.\n";

std::int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

struct Settings {
  std::vector<int> sizes{1000, 10000, 100000};
  std::string backend = "auto", formats, grammar = "grammars/tomato.yaml", dir,
              csv = "bench/results/stand.csv";
  bool glb_compact = false, append = false;
  int threads = 0;
  std::optional<int> steps;
  double disk_mb = 1024;
};

std::string formats_for(const Settings& s, int plants) {
  return !s.formats.empty() ? s.formats : plants > 10000 ? "ply" : "glb";
}

/// The child: one run of `plants` plants; what it measured goes to `result` as JSON.
int run_child(const Settings& s, int plants, std::int64_t spawned_ns, const std::string& result) {
  const double main_s = (now_ns() - spawned_ns) * 1e-9;
  cli::StandOptions o;
  o.grammar = s.grammar;
  o.out = s.dir + "/stand-" + std::to_string(plants);
  o.steps = s.steps;
  o.formats = formats_for(s, plants);
  o.glb_compact = s.glb_compact;
  o.rows.rows = plants < 100 ? 1 : plants / 100;
  o.rows.per_row = plants < 100 ? plants : 100;
  o.rows.row_spacing = 1.0, o.rows.plant_spacing = 0.4, o.rows.jitter = 0.02, o.rows.seed = 1;
  o.random_rotation = true;
  o.detect.backend = s.backend;
  o.detect.threads = s.threads;
  o.ends_process = true;  // as canopy stand: main ends the process (tools/process_end.hpp)
  try {
    const cli::StandOutcome r = cli::run_stand(o, /*print=*/false);
    nlohmann::ordered_json j;
    j["main_s"] = main_s;
    j["returned_s"] = (now_ns() - spawned_ns) * 1e-9;
    j["timings"] = r.report["timings_s"];
    j["peak_memory"] = r.report["peak_memory_gb"];
    j["commit_s"] = r.commit_s;
    j["export_bytes"] = r.export_bytes;
    j["organs"] = r.report["counts"]["organs"];
    j["triangles"] = r.report["counts"]["triangles"];
    j["backend"] = r.report["backend"];
    j["device"] = r.report["device"];
    j["contacts_before"] = r.contacts_before;
    j["contacts_after"] = r.contacts_after;
#ifdef CANOPY_HAVE_CUDA
    j["device_peak_bytes"] = cuda::device_bytes().peak();
#else
    j["device_peak_bytes"] = 0;
#endif
    std::ofstream(result) << j.dump() << "\n";
  } catch (const std::exception& e) {
    fmt::print(stderr, "bench_stand: {} plants: {}\n", plants, e.what());
    return 1;
  }
  return 0;
}

/// This program started again for one size; the parent's view of it.
struct ChildRun {
  int status = -1;
  double wall_s = 0, cpu_s = 0, peak_rss_gb = 0;
  std::int64_t spawned_ns = 0;
};

ChildRun spawn_child(std::vector<std::string> args) {
  ChildRun c;
  c.spawned_ns = now_ns();
  args.insert(args.end(), {"--spawned", std::to_string(c.spawned_ns)});
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawn(&pid, "/proc/self/exe", nullptr, nullptr, argv.data(), environ) != 0) return c;
  int status = 0;
  rusage ru{};
  wait4(pid, &status, 0, &ru);
  c.wall_s = (now_ns() - c.spawned_ns) * 1e-9;
  c.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  c.cpu_s = static_cast<double>(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
            1e-6 * static_cast<double>(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
  c.peak_rss_gb = static_cast<double>(ru.ru_maxrss) * 1024.0 / 1e9;  // kilobytes
  return c;
}

double num(const nlohmann::json& j, const char* key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : 0.0;
}

}  // namespace

int main(int argc, char** argv) {
  Settings s;
  int child = -1;
  std::int64_t spawned = 0;
  std::string result;
  std::vector<std::string> passed;  // the options every child gets
  for (int i = 1; i < argc; ++i) {
    const bool has = i + 1 < argc;
    const std::string a = argv[i];
    if (a == "--sizes" && has) {
      s.sizes.clear();
      for (char* t = std::strtok(argv[++i], ","); t; t = std::strtok(nullptr, ","))
        s.sizes.push_back(std::atoi(t));
      continue;
    }
    if (a == "--csv" && has) s.csv = argv[++i];
    else if (a == "--append") s.append = true;
    else if (a == "--disk-mb" && has) s.disk_mb = std::atof(argv[++i]);
    else if (a == "--child" && has) child = std::atoi(argv[++i]);
    else if (a == "--spawned" && has) spawned = std::atoll(argv[++i]);
    else if (a == "--result" && has) result = argv[++i];
    else if (a == "--backend" && has) passed.insert(passed.end(), {a, s.backend = argv[++i]});
    else if (a == "--formats" && has) passed.insert(passed.end(), {a, s.formats = argv[++i]});
    else if (a == "--grammar" && has) passed.insert(passed.end(), {a, s.grammar = argv[++i]});
    else if (a == "--dir" && has) passed.insert(passed.end(), {a, s.dir = argv[++i]});
    else if (a == "--threads" && has)
      passed.insert(passed.end(), {a, argv[i + 1]}), s.threads = std::atoi(argv[++i]);
    else if (a == "--steps" && has)
      passed.insert(passed.end(), {a, argv[i + 1]}), s.steps = std::atoi(argv[++i]);
    else if (a == "--glb-compact") s.glb_compact = true, passed.push_back(a);
    else return help_or_refuse("bench_stand", argv[i], kUsage);
  }
  if (child >= 0) {
    // As canopy's main: the heap's pages chosen (a rerun of this process) before anything else.
    try {
      rerun_for_run(heap_pages_for(command_runs_on_gpu(argc, argv, "auto")), true, argv);
    } catch (const std::invalid_argument& e) {  // the environment's heap-page choice, misspelt
      std::fprintf(stderr, "bench_stand: error: %s\n", e.what());
      return 2;
    }
    keep_freed_memory();
    return end_process(run_child(s, child, spawned, result));
  }
  for (int n : s.sizes)
    if (n <= 0 || (n > 100 && n % 100)) {
      fmt::print(
          stderr,
          "bench_stand: --sizes: {} is not a size of the default stand (1-100, or a multiple of 100)\n", n);
      return 2;
    }
  const bool own_dir = s.dir.empty();
  if (own_dir) {
    s.dir = (fs::temp_directory_path() / fmt::format("canopy-bench-stand-{}", getpid())).string();
    passed.insert(passed.end(), {"--dir", s.dir});
  }
  fs::create_directories(s.dir);
  const DiskSpeed disk = measure_disk(s.dir, static_cast<std::uint64_t>(s.disk_mb * (1 << 20)));
  fmt::print("disk of {}: {:.2f} GB/s written, {:.2f} GB/s written and synced ({:.0f} MB)\n", s.dir,
             disk.written_gbs, disk.synced_gbs, s.disk_mb * 1.048576);
  std::FILE* out = std::fopen(s.csv.c_str(), s.append ? "a" : "w");
  if (!out) {
    fmt::print(stderr, "bench_stand: cannot write {}\n", s.csv);
    return 1;
  }
  if (!s.append)
    fmt::print(
        out,
        "plants,organs_per_plant,triangles_per_plant,backend,device,threads,formats,end_to_end_s,"
        "startup_s,grow_s,"
        "tree_build_s,upload_s,detect_s,resolve_s,detect_after_s,export_format_s,export_write_s,"
        "export_s,commit_s,"
        "end_s,cpu_s,peak_rss_gb,peak_grow_gb,peak_detect_gb,peak_resolve_gb,peak_export_gb,device_peak_gb,"
        "contacts_before,contacts_after,export_gb,export_gbs,"
        "disk_written_gbs,"
        "disk_synced_gbs,export_of_disk\n");
  fmt::print(
      "{:>7} {:>7} {:>7} {:>6} {:>6} {:>6} {:>6} {:>7} {:>7} {:>6} {:>7} {:>7} {:>6} {:>6} {:>6} {:>7} "
      "{:>6}\n",
      "plants", "total s", "start", "grow", "build", "upload", "detect", "resolve", "after", "format",
      "write", "commit", "end", "rss GB", "dev GB", "exp GB/s", "of disk");
  const int threads = s.threads > 0 ? s.threads : omp_get_max_threads();  // what the runs use
  int failed = 0;
  for (int n : s.sizes) {
    const std::string res = fmt::format("{}/result-{}.json", s.dir, n);
    std::vector<std::string> args{argv[0], "--child", std::to_string(n), "--result", res};
    args.insert(args.end(), passed.begin(), passed.end());
    const ChildRun c = spawn_child(args);
    std::error_code ec;
    fs::remove_all(fmt::format("{}/stand-{}", s.dir, n), ec);
    std::ifstream in(res);
    if (c.status != 0 || !in) {
      fmt::print("{:>7} failed (exit status {}): no row\n", n, c.status);
      ++failed;
      continue;
    }
    const nlohmann::json j = nlohmann::json::parse(in);
    fs::remove(res, ec);
    const nlohmann::json& t = j["timings"];
    const double startup = num(j, "main_s") + num(t, "startup"), build = num(t, "detect_build"),
                 upload = num(t, "detect_upload");
    const double detect = num(t, "detect") - build - upload, exp = num(t, "export"),
                 commit = num(j, "commit_s");
    // The detection after resolution runs while the files are written: not a stage of its own
    // in the wall time (waiting for it, where it outlasts the export, falls in `end`).
    const double staged = num(t, "startup") + num(t, "generate") + num(t, "target") + num(t, "detect") +
                          num(t, "resolve") + exp;
    const double end = c.wall_s - num(j, "main_s") - staged - commit;
    const double gb = num(j, "export_bytes") / 1e9, gbs = exp > 0 ? gb / exp : 0;
    const double organs = num(j, "organs"), tris = num(j, "triangles");
    std::string device = j["device"].is_string() ? j["device"].get<std::string>() : "";
    std::replace(device.begin(), device.end(), ',', ';');  // one CSV field
    const double dev_gb = num(j, "device_peak_bytes") / 1e9;
    const nlohmann::json& m = j["peak_memory"];
    // Each stage's reset of the high-water mark resets wait4's maxrss too: the run's peak is the
    // largest of the stages' and what wait4 saw after the last reset.
    double peak_gb = c.peak_rss_gb;
    if (m.is_object())
      for (const auto& [k, v] : m.items())
        if (v.is_number()) peak_gb = std::max(peak_gb, v.get<double>());
    fmt::print(
        "{:>7} {:>7.2f} {:>7.3f} {:>6.2f} {:>6.3f} {:>6.3f} {:>6.3f} {:>7.2f} {:>7.3f} {:>6.2f} {:>7.2f} "
        "{:>7.3f} {:>6.3f} "
        "{:>6.2f} {:>6.2f} {:>7.2f} {:>6.2f}\n",
        n, c.wall_s, startup, num(t, "generate"), build, upload, detect, num(t, "resolve"),
        num(t, "detect_after"), num(t, "export_format"), num(t, "export_write"), commit, end, peak_gb, dev_gb,
        gbs, gbs / disk.synced_gbs);
    fmt::print("{:>7} peak resident GB by stage: grow {:.2f}, detect {:.2f}, resolve {:.2f}, export {:.2f}\n",
               "", num(m, "generate"), num(m, "detect"), num(m, "resolve"), num(m, "export"));
    fmt::print(
        out,
        "{},{:.1f},{:.1f},{},{},{},{},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{"
        ":.4f},{:.4f},{:.4f},"
        "{:.4f},{:.2f},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{},{},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f}\n",
        n, organs / n, tris / n, j["backend"].get<std::string>(), device, threads, formats_for(s, n),
        c.wall_s, startup, num(t, "generate"), build, upload, detect, num(t, "resolve"),
        num(t, "detect_after"), num(t, "export_format"), num(t, "export_write"), exp, commit, end, c.cpu_s,
        peak_gb, num(m, "generate"), num(m, "detect"), num(m, "resolve"), num(m, "export"), dev_gb,
        num(j, "contacts_before"), num(j, "contacts_after"), gb, gbs, disk.written_gbs, disk.synced_gbs,
        gbs / disk.synced_gbs);
    std::fflush(out);
  }
  std::fclose(out);
  if (own_dir) fs::remove_all(s.dir);
  fmt::print("wrote {}\n", s.csv);
  return failed ? 1 : 0;
}
