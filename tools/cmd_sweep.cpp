// canopy sweep: a spacing / density x age experiment, several seeds per cell, one CSV row per
// run (resumable), and a summary per cell.
#include "geometry/atomic_file.hpp"
#include "geometry/clock.hpp"
#include "geometry/layout.hpp"
#include "geometry/stand_metrics.hpp"
#include "geometry/thread_limit.hpp"
#include "lsystem/grow.hpp"
#include "tools/cli_common.hpp"
#include "tools/detect_options.hpp"
#include "tools/json_text.hpp"
#include "tools/resolve_options.hpp"
#include "tools/signals.hpp"
#include "tools/sweep_spec.hpp"
#include "tools/sweep_light.hpp"
#include "tools/sweep_run.hpp"
#include "tools/sweep_settings.hpp"
#include "tools/sweep_table.hpp"

#ifdef CANOPY_WITH_MPI
#include "distributed/mpi_comm.hpp"
#endif

#include <fmt/format.h>
#include <fcntl.h>
#include <nlohmann/json.hpp>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <atomic>
#include <charconv>
#include <chrono>
#include <cmath>
#include <csignal>
#include <map>
#include <optional>
#include <filesystem>
#include <set>

namespace canopy::cli {
namespace {

std::atomic<bool> g_interrupted{false};

std::string num(double v) { return fmt::format("{}", v); }

/// Rows of an earlier sweep whose cell is one of this sweep's within a rounding (ranges wrote
/// 0.30000000000000004 before they were tidied to 0.3) take this sweep's text for its spacings,
/// so that resuming finds them done and the summary keeps one cell. A row is matched by its
/// plant and row spacing together; one whose text is a cell's exactly keeps it (densities give
/// spacings of other cells one rounding apart: 1/(2 x 0.6) and 1/(1.5 x 0.8)), and no row takes
/// the key of another.
void adopt_spacings(std::vector<RunRow>& rows, const std::vector<SweepCell>& cells) {
  const auto value = [](const std::string& text) -> std::optional<double> {
    std::size_t used = 0;
    const double v = leading_number(text, used);
    if (used == 0 || used != text.size()) return std::nullopt;
    return v;
  };
  // Tidied range values moved by at most half a unit of their 12th digit: 5e-12 relative.
  const auto near = [](double v, double w) { return std::abs(v - w) <= 1e-11 * std::abs(w); };
  std::set<std::string> exact, keys;
  for (const SweepCell& c : cells) exact.insert(num(c.plant_spacing) + "|" + num(c.row_spacing));
  for (const RunRow& r : rows) keys.insert(run_key(r));
  for (RunRow& r : rows) {
    if (exact.count(r["plant_spacing"] + "|" + r["row_spacing"])) continue;
    const auto p = value(r["plant_spacing"]), w = value(r["row_spacing"]);
    if (!p || !w) continue;
    for (const SweepCell& c : cells) {
      if (!near(*p, c.plant_spacing) || !near(*w, c.row_spacing)) continue;
      RunRow adopted = r;
      adopted["plant_spacing"] = num(c.plant_spacing), adopted["row_spacing"] = num(c.row_spacing);
      if (keys.insert(run_key(adopted)).second) r = std::move(adopted);
      break;
    }
  }
}

/// The row layout of a cell's run of seed `seed`.
RowLayout cell_layout(const SweepOptions& o, const SweepCell& cell, int seed) {
  RowLayout layout;
  layout.rows = o.rows;
  layout.per_row = o.per_row;
  layout.plant_spacing = cell.plant_spacing;
  layout.row_spacing = cell.row_spacing;
  layout.jitter = o.jitter.value();  // filled in by run_sweep
  layout.random_rotation = o.random_rotation.value();
  layout.seed = static_cast<std::uint64_t>(seed);
  return layout;
}

/// Refuses, before any run, a cell whose plants would stand farther from the origin than a
/// stand's may (each of its runs would fail alike); a density names itself and its spacing.
void check_cells_reach(const SweepOptions& o, const std::vector<SweepCell>& cells, bool by_density) {
  for (const SweepCell& cell : cells) try {
      check_reach(cell_layout(o, cell, 0));
    } catch (const std::invalid_argument& e) {
      if (!by_density) throw;
      throw std::invalid_argument(
          fmt::format("--density {:g} plants/m2 (a plant spacing of {:g} m at a row "
                      "spacing of {:g} m): {}",
                      cell.density, cell.plant_spacing, cell.row_spacing, e.what()));
    }
}

/// One run: grow, detect (every level up to the exact one), resolve; the row of runs.csv.
RunRow run_one(const SweepOptions& o, const SweepCell& cell, int seed, DetectionBackend& backend,
               RunRow row) {
  const RowLayout layout = cell_layout(o, cell, seed);
  GrowRequest req = grow_request(o.grammar, o.set, cell.steps, o.lod, o.detect.threads, o.max_modules);
  req.plants = row_layout(layout);
  auto t = std::chrono::steady_clock::now();
  Stand stand = grow_stand(req);
  row["generate_s"] = fmt::format("{:.4f}", seconds_since(t));
  PrototypeLibrary lib;
  const LeafAreaIndex lai =
      leaf_area_index(stand, lib, o.rows, o.per_row, cell.plant_spacing, cell.row_spacing);
  const double n = static_cast<double>(stand.plant_count());
  row["plants"] = std::to_string(stand.plant_count());
  row["organs"] = std::to_string(stand.organ_count());
  row["lai"] = fmt::format("{:.5f}", lai.lai);
  row["lai_plants"] = std::to_string(lai.plants);
  double light_s = o.no_light ? 0.0 : light_columns(stand, layout, o, "before", row);
  DetectRequest dreq = o.detect.request();
  dreq.level = ContactLevel::exact;
  t = std::chrono::steady_clock::now();
  const Contacts c = backend.detect(stand, dreq);
  row["detect_s"] = fmt::format("{:.4f}", seconds_since(t));
  for (std::size_t l = 0; l < 4; ++l) {
    const std::string level(kContactLevelNames[l]);
    row[level + "_between_per_plant"] = fmt::format("{:.4f}", static_cast<double>(c.counts[l]->between) / n);
    row[level + "_within_per_plant"] = fmt::format("{:.4f}", static_cast<double>(c.counts[l]->within) / n);
  }
  if (!o.resolve.no_resolve) {
    ResolveOptions ro = o.resolve;
    ro.progress = false;
    const ResolveConfig rc = ro.config();
    DetectRequest at = dreq;
    at.level = rc.level;
    const Contacts start = rc.level == ContactLevel::exact ? c : backend.detect(stand, at);
    t = std::chrono::steady_clock::now();
    const ResolveResult r = run_resolution(stand, backend, dreq, ro, start);
    row["resolve_s"] = fmt::format("{:.4f}", seconds_since(t));
    row["organs_turned"] = std::to_string(r.organs_moved);
    row["organs_turned_per_plant"] = fmt::format("{:.4f}", static_cast<double>(r.organs_moved) / n);
    row["mean_turn_deg"] = fmt::format("{:.4f}", r.mean_turn_deg);
    row["max_turn_deg"] = fmt::format("{:.4f}", r.max_turn_deg);
    row["rounds"] = std::to_string(r.rounds);
    // What is left, at the exact level: resolution's own list when it resolved at that level,
    // else a detection from scratch.
    row["residual_contacts"] = std::to_string(
        rc.level == ContactLevel::exact ? r.contacts_after : backend.detect(stand, dreq).pairs.size());
    if (!o.no_light) light_s += light_columns(stand, layout, o, "after", row);
  }
  if (!o.no_light) row["light_s"] = fmt::format("{:.4f}", light_s);
  row["status"] = "ok";
  return row;
}

}  // namespace

SweepOutcome run_sweep(const SweepOptions& given, bool print, const SweepCallback& after_run,
                       const SweepRanks* ranks) {
  SweepOptions o = given;
  const ThreadLimit thread_limit(o.detect.threads);
  const int me = ranks ? ranks->rank : 0, team = ranks ? ranks->size : 1;
  print = print && me == 0;
  std::string note;
  // The specification first: bad lists fail before any work.
  const auto rows_sp = parse_number_list("--row-spacing", o.row_spacing, 0, true);
  std::vector<double> plant_sp, dens;
  if (!o.density.empty()) dens = parse_number_list("--density", o.density, 0, true);
  else plant_sp = parse_number_list("--plant-spacing", o.plant_spacing, 0, true);
  std::vector<std::optional<int>> steps{std::nullopt};
  if (!o.steps.empty()) {
    steps.clear();
    for (double s : parse_number_list("--steps", o.steps, 0, false)) {
      if (s != std::floor(s))
        throw std::invalid_argument(fmt::format("--steps: {} is not a whole number", s));
      if (s > kMaxSteps)
        throw std::invalid_argument(
            fmt::format("--steps: {} is more than the {} steps a plant may grow", s, kMaxSteps));
      steps.push_back(static_cast<int>(s));
    }
  }
  // The runs asked for, bounded before any list of them is made (a few ranges multiply fast).
  const double runs = static_cast<double>(rows_sp.size()) *
                      static_cast<double>(dens.empty() ? plant_sp.size() : dens.size()) *
                      static_cast<double>(steps.size()) * static_cast<double>(o.seeds);
  if (runs > kMaxSweepRuns)
    throw std::invalid_argument(fmt::format(
        "sweep: {} row spacings x {} {} x {} ages x {} seeds = {:.15g} runs, more than the {:.0f} a sweep "
        "takes: "
        "give shorter lists or fewer seeds",
        rows_sp.size(), dens.empty() ? plant_sp.size() : dens.size(),
        dens.empty() ? "plant spacings" : "densities", steps.size(), o.seeds, runs, kMaxSweepRuns));
  (void)o.detect.request();
  check_sweep_light(o);
  const LoadOptions load = [&] {
    LoadOptions l;
    for (const auto& s : o.set) l.overrides.push_back(parse_override(s));
    return l;
  }();
  const Grammar g = load_grammar(o.grammar, load);
  if (print) print_notes(g.notes);
  std::vector<std::string> notes = g.notes;
  // Jitter and rotation: the options', else the grammar's stand entry's, else the default stand's.
  const StandSpec entry = g.stand.value_or(StandSpec{});
  const char* jitter_from = o.jitter ? "command line" : entry.jitter ? "grammar" : "default";
  const char* rotation_from = o.random_rotation       ? "command line"
                              : entry.random_rotation ? "grammar"
                                                      : "default";
  if (!o.jitter) o.jitter = entry.jitter.value_or(0.02);
  if (!o.random_rotation) o.random_rotation = entry.random_rotation.value_or(true);
  if (!(*o.jitter >= 0) || !std::isfinite(*o.jitter))
    throw std::invalid_argument(
        fmt::format("--jitter must be a finite number of metres, at least 0 (got {})", *o.jitter));
  const std::vector<SweepCell> cells = sweep_cells(rows_sp, plant_sp, dens, steps);
  check_cells_reach(o, cells, !dens.empty());
  auto backend = make_backend(o.detect.backend, note, ranks ? ranks->local_rank : 0);

  const std::string runs_path = o.out + "/runs.csv";
  std::set<std::string> finished;
  // A run of this call's grid as runs.csv keys it, and the keys of every run it asks for, made or not.
  const auto grid_row = [&](const SweepCell& cell, int seed) {
    RunRow row;
    row["plant_spacing"] = num(cell.plant_spacing);
    row["row_spacing"] = num(cell.row_spacing);
    row["density"] = fmt::format("{:.4f}", cell.density);
    row["steps"] = std::to_string(cell.steps.value_or(g.steps));
    row["seed"] = std::to_string(seed);
    row["backend"] = backend->name();
    return row;
  };
  std::set<std::string> grid;
  for (const SweepCell& cell : cells)
    for (int seed = 1; seed <= o.seeds; ++seed) grid.insert(run_key(grid_row(cell, seed)));
  std::map<std::string, std::string> numbers;  // run key -> its number in runs.csv
  std::uint64_t next_number = 0;               // the first number no row has
  // Rank 0 reads runs.csv and tells the others what is done, or why the sweep cannot go on: then
  // every rank stops with that error instead of waiting for rank 0.
  std::string answer;
  // Rank 0's lock on the folder, let go when the sweep ends (the Python module runs sweeps one
  // after another in one process) or, killed, with the process.
  struct FolderLock {
    int fd = -1;
    ~FolderLock() {
      if (fd >= 0) ::close(fd);
    }
  } sweep_lock;
  if (me == 0) {
    nlohmann::json a;
    try {
      std::error_code made;
      std::filesystem::create_directories(o.out, made);
      if (made || !std::filesystem::is_directory(o.out))
        throw std::runtime_error(fmt::format("cannot create the sweep folder {}: {}", o.out,
                                             made ? made.message() : "it exists and is not a folder"));
      // One sweep writes a folder at a time: two at once each ran every cell and appended its own
      // rows, and summary.csv pooled the duplicates. The lock is a file of the folder's,
      // .sweep.lock (flock, held by sweep_lock until the sweep returns; the kernel lets it go
      // however the process ends): a stand run that replaces the folder links its files into the
      // new one, the lock's among them, where a lock on the folder itself stayed with the folder
      // swapped away and a second sweep ran beside the first.
      sweep_lock.fd =
          ::open((std::filesystem::path(o.out) / ".sweep.lock").c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
      if (sweep_lock.fd >= 0 && ::flock(sweep_lock.fd, LOCK_EX | LOCK_NB) != 0 && errno == EWOULDBLOCK)
        throw std::invalid_argument(fmt::format(
            "sweep: another canopy sweep is writing {}; wait for it to end, or give another -o", o.out));
      std::vector<RunRow> done = read_runs(runs_path);
      check_sweep_settings(o.out, sweep_settings(o), done.size());
      // Spacings first: a run is known by its key with this sweep's text for its cell, also a
      // failed run retried below.
      adopt_spacings(done, cells);
      // A run keeps its number, a retried one too; runs new to the folder take the numbers after
      // the largest (numbering them by their place in a grown grid gave two runs one number).
      std::map<std::string, std::string> held;  // run key -> number, as rank 0 read them
      std::uint64_t next = 0;
      for (const RunRow& r : done) {
        const std::string& n = r.at("run");
        std::uint64_t v = 0;
        if (std::from_chars(n.data(), n.data() + n.size(), v).ptr == n.data() + n.size() && !n.empty())
          next = std::max(next, v + 1);
        held[run_key(r)] = n;
      }
      a["numbers"] = held, a["next"] = next;
      // Only this call's failed runs are run again: failed rows of cells it does not ask for stay.
      if (o.retry_failed)
        std::erase_if(done,
                      [&](const RunRow& r) { return r.at("status") != "ok" && grid.count(run_key(r)); });
      write_runs(runs_path, done);  // drops a torn last line
      std::set<std::string> keys;
      for (const RunRow& r : done) keys.insert(run_key(r));
      a["finished"] = keys;
    } catch (const std::invalid_argument& e) {
      a["error"] = e.what(), a["bad_input"] = true;
    } catch (const std::exception& e) {
      a["error"] = e.what(), a["bad_input"] = false;
    }
    answer = json_text(a);
  }
  if (ranks) answer = ranks->gather(answer)[0];
  {
    const nlohmann::json a = nlohmann::json::parse(answer);
    if (a.contains("error")) {
      if (a["bad_input"].get<bool>()) throw std::invalid_argument(a["error"].get<std::string>());
      throw std::runtime_error(a["error"].get<std::string>());
    }
    finished = a["finished"].get<std::set<std::string>>();
    numbers = a["numbers"].get<std::map<std::string, std::string>>();
    next_number = a["next"].get<std::uint64_t>();
  }

  const std::size_t total = cells.size() * static_cast<std::size_t>(o.seeds);
  if (print)
    fmt::print(
        "sweep: {} cells x {} seeds = {} runs of {} x {} plants (jitter {} m from the {}, random rotation {} "
        "from the {}), "
        "{} already done; backend {}\n",
        cells.size(), o.seeds, total, o.rows, o.per_row, *o.jitter, jitter_from,
        *o.random_rotation ? "on" : "off", rotation_from, finished.size(), note);
  const bool tty = print && isatty(fileno(stderr));
  g_interrupted = false;
  // Ctrl-C ends the sweep after the run in progress (the command line only: a host program such
  // as Python keeps its own handler).
  std::optional<SoftInterrupt> soft;
  if (print) soft.emplace(g_interrupted);  // a second Ctrl-C stops at once
  std::exception_ptr stopped;
  const auto t0 = std::chrono::steady_clock::now();
  std::size_t ran = 0, failed = 0;
  // The runs still to make, in run order.
  struct Pending {
    std::size_t index;
    const SweepCell* cell;
    int seed;
    RunRow row;
  };
  std::vector<Pending> pending;
  std::size_t index = 0;
  for (const SweepCell& cell : cells)
    for (int seed = 1; seed <= o.seeds; ++seed, ++index) {
      RunRow row = grid_row(cell, seed);
      const std::string key = run_key(row);
      if (finished.count(key)) continue;
      const auto known = numbers.find(key);
      row["run"] = known != numbers.end() ? known->second : std::to_string(next_number++);
      pending.push_back({index, &cell, seed, std::move(row)});
    }
  // Waves of one run per rank; the rows of a wave are appended in run order by rank 0.
  for (std::size_t wave = 0; wave < pending.size() && !stopped; wave += static_cast<std::size_t>(team)) {
    if (ranks) {
      const auto flags = ranks->gather(g_interrupted ? "1" : "0");
      g_interrupted = std::find(flags.begin(), flags.end(), "1") != flags.end();
    }
    if (g_interrupted) break;
    std::string mine;
    if (wave + static_cast<std::size_t>(me) < pending.size()) {
      Pending& p = pending[wave + static_cast<std::size_t>(me)];
      if (tty)
        fmt::print(
            stderr,
            "\r  sweep: run {}/{} (plant spacing {} m, row spacing {} m, steps {}, seed {}), {:.0f} s   ",
            p.index + 1, total, p.row["plant_spacing"], p.row["row_spacing"], p.row["steps"], p.seed,
            seconds_since(t0));
      try {
        p.row = run_one(o, *p.cell, p.seed, *backend, p.row);
      } catch (const std::exception& e) {
        p.row["status"] = "failed";
        p.row["message"] = e.what();
      }
      mine = json_text(nlohmann::json(p.row));
    }
    const std::vector<std::string> rows = ranks ? ranks->gather(mine) : std::vector<std::string>{mine};
    for (std::size_t k = 0; k < rows.size() && wave + k < pending.size(); ++k) {
      const Pending& p = pending[wave + k];
      const RunRow row = nlohmann::json::parse(rows[k]).get<RunRow>();
      if (me == 0) append_run(runs_path, row);
      ++ran;
      if (row.at("status") != "ok") ++failed;
      if (after_run && !stopped) {
        try {
          after_run(p.index, total, row);
        } catch (...) {
          stopped = std::current_exception();
        }
      }
      if (print && !tty)
        fmt::print("run {}/{}: plant spacing {} m, row spacing {} m, steps {}, seed {}: {}\n", p.index + 1,
                   total, row.at("plant_spacing"), row.at("row_spacing"), row.at("steps"), p.seed,
                   row.at("status") == "ok"
                       ? fmt::format("LAI {}, {} exact contacts between plants per plant", row.at("lai"),
                                     row.at("exact_between_per_plant"))
                       : "failed: " + row.at("message"));
    }
  }
  soft.reset();
  if (tty) fmt::print(stderr, "\r{:100}\r", "");
  if (ranks) ranks->gather("");  // every row is in runs.csv before rank 0 reads it back
  const std::vector<RunRow> all = me == 0 ? read_runs(runs_path) : std::vector<RunRow>{};
  if (me == 0) {
    AtomicFile summary(o.out + "/summary.csv");
    summary.write(summary_csv(all));
    summary.commit();
  }
  // Runs of this call's grid recorded as failed, made now or kept from an earlier call (rank 0
  // reads the table; the other ranks know this call's). A table's failed rows of cells this call
  // does not ask for (a sweep resumed with another grid) are not its runs.
  std::size_t failed_rows = failed;
  if (me == 0) {
    std::vector<RunRow> keyed = all;
    adopt_spacings(keyed, cells);  // the earlier text of a spacing, as the runs were matched
    failed_rows = std::count_if(keyed.begin(), keyed.end(), [&](const RunRow& r) {
      return r.at("status") != "ok" && grid.count(run_key(r));
    });
  }
  if (print) {
    fmt::print("sweep: {} runs made now ({} failed), {} in {} of {}; {:.1f} s\n", ran, failed, all.size(),
               runs_path, total, seconds_since(t0));
    if (failed_rows > failed)
      fmt::print(
          "sweep: {} runs of {} are recorded as failed by an earlier call; --retry-failed runs them "
          "again\n",
          failed_rows - failed, runs_path);
  }
  if (stopped) std::rethrow_exception(stopped);
  SweepOutcome out;
  out.total = total, out.ran = ran, out.failed = failed, out.failed_in_table = failed_rows;
  out.notes = std::move(notes);
  out.interrupted = g_interrupted;
  if (g_interrupted) {
    if (print) fmt::print("interrupted: run the same command again to go on where it stopped\n");
    out.exit_code = 130;
  } else {
    out.exit_code = failed_rows ? 3 : 0;
  }
  return out;
}

std::shared_ptr<SweepOptions> register_sweep(CLI::App& app_ref) {
  CLI::App* app = &app_ref;
  auto o = std::make_shared<SweepOptions>();
  app->add_option("GRAMMAR", o->grammar, "Grammar file (YAML)")->required();
  app->add_option("-o,--out", o->out,
                  "Output folder: runs.csv, summary.csv (default sweep); an existing one is resumed");
  app->add_option("--plant-spacing", o->plant_spacing,
                  "Metres between plants in a row: a list a,b,c or a range start:stop:step (default 0.4)");
  app->add_option("--row-spacing", o->row_spacing, "Metres between rows: list or range (default 1.0)");
  app->add_option("--density", o->density,
                  "Plants per m2 (list or range) instead of --plant-spacing: plant spacing = 1 / (density x "
                  "row spacing)")
      ->excludes("--plant-spacing");
  app->add_option("--steps", o->steps,
                  "Plant ages in derivation steps: list or range (default: the grammar's)");
  app->add_option("--seeds", o->seeds, "Stand seeds per cell, 1..N (default 3)")
      ->transform(whole_in(1, INT32_MAX));
  app->add_option("--rows", o->rows, "Rows per stand (default 3)")->transform(whole_in(1, INT32_MAX));
  app->add_option("--per-row", o->per_row, "Plants per row (default 5)")->transform(whole_in(1, INT32_MAX));
  app->add_option("--jitter", o->jitter,
                  "Jitter radius in metres (default: the grammar's stand entry, else 0.02; plants are turned "
                  "at random unless "
                  "the grammar's stand entry says otherwise)")
      ->check(kFinite)
      ->check(at_least(0));
  CLI::Option* turned = app->add_flag_callback(
      "--random-rotation", [o] { o->random_rotation = true; },
      "Turn each plant by a random angle about Z (the default unless the grammar's stand entry says "
      "otherwise)");
  app->add_flag_callback(
         "--no-random-rotation", [o] { o->random_rotation = false; },
         "Every plant facing the same way (overrides the grammar's stand entry)")
      ->excludes(turned);
  app->add_option("--lod", o->lod, "Level of detail (default 2)")->transform(whole_in(1, kMaxLod));
  app->add_option("--set", o->set, "Override a grammar constant: NAME=VALUE (repeatable)");
  app->add_option("--max-modules", o->max_modules,
                  "Module cap per plant derivation (a run past it is recorded as failed)")
      ->transform(whole_in(1, INT64_MAX));
  app->add_flag("--retry-failed", o->retry_failed, "On resuming, run again the runs recorded as failed");
  CLI::Option* sun = app->add_option(
      "--sun", o->sun, "Light columns: the direct beam ELEVATION,AZIMUTH in degrees (default 60,180)");
  CLI::Option* sky = app->add_option("--sky", o->sky, "Light columns: sky radiance soc (default) or uniform");
  CLI::Option* sky_directions =
      app->add_option("--sky-directions", o->sky_directions, "Light columns: sky directions (default 46)")
          ->transform(whole_in(1, 10000));
  CLI::Option* light_error =
      app->add_option("--light-error", o->light_error,
                      "Light columns: standard error asked of the stand's fractions (default 0.002)")
          ->check(kFinite);
  // The light options say how the light columns are made: with --no-light there are none, and a
  // setting given there would be read (and its mistakes kept) by no one.
  app->add_flag("--no-light", o->no_light, "Leave the light columns empty")
      ->excludes(sun)
      ->excludes(sky)
      ->excludes(sky_directions)
      ->excludes(light_error);
  o->detect.add_to(*app);
  o->resolve.add_to(*app);
  return o;
}

Command add_sweep(CLI::App& root) {
  CLI::App* app = root.add_subcommand(
      "sweep", "Run a spacing / density x age experiment: one CSV row per run, a summary per cell");
  auto o = register_sweep(*app);
  return {app, [o]() {
#ifdef CANOPY_WITH_MPI
            if (mpi::launched()) {
              SweepRanks ranks{mpi::rank(), mpi::size(), mpi::local_rank(), [](const std::string& mine) {
                                 std::vector<std::size_t> starts;
                                 const std::vector<char> all =
                                     mpi::allgather_bytes(mine.data(), mine.size(), &starts);
                                 std::vector<std::string> out;
                                 for (std::size_t r = 0; r + 1 < starts.size(); ++r)
                                   out.emplace_back(all.data() + starts[r], starts[r + 1] - starts[r]);
                                 return out;
                               }};
              return run_sweep(*o, true, {}, &ranks).exit_code;
            }
#endif
            return run_sweep(*o).exit_code;
          }};
}

}  // namespace canopy::cli
