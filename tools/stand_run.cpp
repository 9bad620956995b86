// canopy stand's run: grow, detect, resolve, export, report.
#include "geometry/clock.hpp"
#include "tools/json_text.hpp"
#include "geometry/export.hpp"
#include "geometry/input_file.hpp"
#include "geometry/layout.hpp"
#include "geometry/split_list.hpp"
#include "geometry/thread_limit.hpp"
#include "lsystem/grow.hpp"
#include "tools/cli_common.hpp"
#include "tools/detect_options.hpp"
#include "tools/heap_pages.hpp"
#include "tools/process_end.hpp"
#include "tools/report.hpp"
#include "tools/resolve_options.hpp"
#include "tools/stand_run.hpp"
#include "tools/stage_memory.hpp"
#ifdef CANOPY_HAVE_CUDA
#include "cuda/device.hpp"
#endif

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <deque>
#include <filesystem>
#include <future>
#include <set>
#include <thread>

namespace canopy::cli {
std::set<std::string> parse_formats(const std::string& list) {
  std::set<std::string> formats;
  for (const std::string& f : split_list(list)) {
    if (f != "glb" && f != "obj" && f != "ply")
      throw std::invalid_argument(fmt::format("--formats: unknown format '{}' (expected glb, obj, ply)", f));
    formats.insert(f);
  }
  return formats;
}

namespace {

// The mesh files' names, written by write_stand_files and replaced as a set (stand_folder_files).
constexpr const char* kGlbFile = "stand.glb";
constexpr const char* kObjFile = "stand.obj";
constexpr const char* kMtlFile = "stand.mtl";  // the OBJ's material library, beside it
constexpr const char* kPlyFile = "stand.ply";

}  // namespace

GlbForm glb_form(bool instancing, bool compact, double resolve_clearance) {
  if (instancing && compact)
    throw std::invalid_argument("--glb-instancing and --glb-compact are two forms of stand.glb: choose one");
  GlbForm g{instancing, compact, {}};
  if (resolve_clearance > 0) g.compact_config.max_step = resolve_clearance / 2;
  return g;
}

void check_glb_written(bool instancing, bool compact, const std::string& formats, const OptionNames& names) {
  // A form of a file not written would be taken without a word (and echoed into report.json).
  if ((instancing || compact) && !parse_formats(formats).count("glb"))
    throw std::invalid_argument(fmt::format("{} is a form of stand.glb, and {} {} writes none: add glb",
                                            compact ? names.compact : names.instancing, names.formats,
                                            formats));
}

GlbForm glb_form(const StandOptions& o) {
  check_glb_written(o.glb_instancing, o.glb_compact, o.formats,
                    {"--glb-instancing", "--glb-compact", "--formats"});
  return glb_form(o.glb_instancing, o.glb_compact, o.resolve.clearance);
}

void write_stand_files(const ExportScope& scope, PrototypeLibrary& lib, const std::set<std::string>& formats,
                       const OpenChunks& open, const GlbForm& glb) {
  if (formats.count("glb")) {
    if (glb.compact) write_glb_compact(scope, lib, open(kGlbFile), glb.compact_config);
    else write_glb(scope, lib, open(kGlbFile));
  }
  if (formats.count("obj")) {
    ChunkWriter& obj = open(kObjFile);
    write_obj(scope, lib, obj, open(kMtlFile), kMtlFile);
  }
  if (formats.count("ply")) write_ply(scope, lib, open(kPlyFile));
  write_organs_csv(scope, lib, open("organs.csv"));
  write_plants_csv(scope, open("plants.csv"));
}

void write_stand_files(const Stand& stand, PrototypeLibrary& lib, const std::set<std::string>& formats,
                       const GlbForm& glb, OutputSet& files) {
  std::set<std::string> chunked = formats;
  if (glb.instancing && chunked.erase("glb")) write_glb_instanced(stand, lib, files.open(kGlbFile));
  std::deque<ChunkFile> opened;
  write_stand_files(
      ExportScope::whole(stand), lib, chunked,
      [&](const std::string& name) -> ChunkWriter& { return opened.emplace_back(files.open(name)); }, glb);
}

const std::vector<std::string>& stand_folder_files() {
  static const std::vector<std::string> names{
      kGlbFile,      kObjFile,     kMtlFile,       kPlyFile,
      "organs.csv",  "plants.csv", "contacts.csv", "contacts_after.csv",
      "report.json", "light.csv",  "light.json"};
  return names;
}

void refuse_stand_file(const std::string& option, const std::string& path) {
  namespace fs = std::filesystem;
  // Through links: a link to a stand's plants.csv would be written through.
  std::error_code ec;
  fs::path file = fs::weakly_canonical(path, ec);
  if (ec) file = path;
  const fs::path folder = file.has_parent_path() ? file.parent_path() : fs::path(".");
  const auto& names = stand_folder_files();
  if (std::find(names.begin(), names.end(), file.filename().string()) == names.end()) return;
  if (!fs::exists(folder / kStandFolderMarker, ec)) return;
  throw std::invalid_argument(
      fmt::format("{} {}: that is the stand folder's own {}, which this would replace; name another file",
                  option, path, file.filename().string()));
}

void refuse_file_place(const std::string& option, const std::string& path, const std::string& kind) {
  namespace fs = std::filesystem;
  const fs::path out(path);
  const fs::path parent = out.has_parent_path() ? out.parent_path() : fs::path(".");
  if (fs::is_directory(out))
    throw std::invalid_argument(
        fmt::format("{} {}: a folder; name the {} file to write", option, path, kind));
  if (!fs::is_directory(parent))
    throw std::invalid_argument(fmt::format("{} {}: {} to write it in", option, path,
                                            fs::exists(parent) ? parent.string() + " is a file, not a folder"
                                                               : "there is no folder " + parent.string()));
}

std::vector<RunInput> plan_inputs(const StandPlan& plan, const StandOptions& o) {
  std::vector<RunInput> in{{"the grammar", o.grammar}};
  if (!o.positions.empty()) in.push_back({"the positions file", o.positions});
  std::set<std::string> named;
  for (const PlantPlacement& p : plan.request.plants)
    if (!p.grammar.empty() && named.insert(p.grammar).second)
      in.push_back({"a grammar the positions file names", grammar_path(plan.request, p.grammar)});
  return in;
}

void refuse_output_over_inputs(const std::vector<RunInput>& inputs, const std::string& out_dir,
                               const std::string& out_file) {
  namespace fs = std::filesystem;
  std::vector<fs::path> outputs;
  if (!out_file.empty()) outputs.emplace_back(out_file);
  if (!out_dir.empty())
    for (const std::string& n : stand_folder_files()) outputs.push_back(fs::path(out_dir) / n);
  for (const RunInput& in : inputs)
    for (const fs::path& out : outputs) {
      std::error_code ec;
      if (!fs::equivalent(in.path, out, ec) || ec) continue;  // either missing: not the same file
      throw std::invalid_argument(
          fmt::format("-o {}: this would replace {}, {} this run reads; write elsewhere or move it first",
                      out_file.empty() ? out_dir : out_file, out.string(), in.what));
    }
}

void print_folder_changes(const StagedFolder& folder, const StagedFolder::Committed& committed) {
  const auto list = [](const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
    return out;
  };
  // In stand_folder_files()'s order: stand.obj before stand.mtl.
  std::vector<std::string> meshes, others;
  for (const std::string& n : stand_folder_files())
    if (std::find(committed.dropped.begin(), committed.dropped.end(), n) != committed.dropped.end())
      (n.starts_with("stand.") ? meshes : others).push_back(n);
  if (!meshes.empty())
    fmt::print("removed {} left by an earlier run (a format not asked for this time)\n", list(meshes));
  if (!others.empty()) fmt::print("removed {}, which described the earlier stand\n", list(others));
  if (!folder.leftovers_removed().empty())
    fmt::print("removed what interrupted runs left beside {}: {}\n", folder.dir(),
               list(folder.leftovers_removed()));
  for (const std::string& note : folder.leftover_notes()) fmt::print(stderr, "canopy: note: {}\n", note);
  for (const std::string& note : committed.notes) fmt::print(stderr, "canopy: note: {}\n", note);
}

StandPlan plan_stand(StandOptions& o) {
  if (o.random_rotation && o.no_random_rotation)
    throw std::invalid_argument("--random-rotation and --no-random-rotation cannot be combined");
  if (o.random_rotation) o.rows.random_rotation = true;
  if (o.no_random_rotation) o.rows.random_rotation = false;
  if (!o.positions.empty() && any_row_option(o.rows))
    throw std::invalid_argument("--positions cannot be combined with row options");
  StandPlan plan;
  plan.request = grow_request(o.grammar, o.set, o.steps, o.lod, o.detect.threads, o.max_modules);
  plan.grammar = load_grammar(o.grammar, plan.request.load);
  // The grammar's stand entry may name a positions file (relative to the grammar's folder): the
  // layout when the command line gives none.
  std::string named_at;  // where the grammar names the positions file, if it does
  if (o.positions.empty() && !any_row_option(o.rows) && plan.grammar.stand && plan.grammar.stand->positions) {
    o.positions = (std::filesystem::path(o.grammar).parent_path() / *plan.grammar.stand->positions).string();
    const auto it = plan.grammar.stand->where.find("positions");
    named_at = it != plan.grammar.stand->where.end() ? it->second : o.grammar;
  }
  if (!o.positions.empty()) {
    try {
      plan.request.plants = read_positions(o.positions, o.any_grammar_path);
    } catch (const FileNotFound& e) {
      // A file the grammar names: the refusal starts with the grammar's place, as its other errors do.
      if (named_at.empty()) throw;
      throw FileNotFound(fmt::format("{}: stand: positions: {}", named_at, e.what()));
    } catch (const InputRefused& e) {
      if (named_at.empty()) throw;
      throw InputRefused(fmt::format("{}: stand: positions: {}", named_at, o.positions), e.line(),
                         e.reason());
    }
    // An empty stand is a stand (its files are valid), but a header alone is more often a file
    // cut short or not yet filled than one asked for.
    if (plan.request.plants.empty())
      plan.grammar.notes.push_back(
          fmt::format("{} holds a header and no plants: the stand is empty", o.positions));
    plan.request.relative_to = std::filesystem::path(o.positions).parent_path().string();
    plan.request.positions_file = o.positions;
  } else {
    // Command-line row options override the grammar's stand entry field by field.
    LayoutChoice choice = choose_layout(o.rows, plan.grammar.stand);
    plan.layout = choice.layout;
    plan.layout_sources = std::move(choice.sources);
  }
  return plan;
}

void check_target(const StandOptions& o) {
  const TargetOptions& t = o.target;
  if (t.error && !(*t.error >= 1e-5 && *t.error <= 0.5))
    throw std::invalid_argument(fmt::format("--target-error: {} is not in 1e-05..0.5", *t.error));
  if (!t.set()) {
    if (t.error)
      throw std::invalid_argument(
          "--target-error: the standard error of --target-ground-cover's estimates; give that target too");
    return;
  }
  if (!o.positions.empty())
    throw std::invalid_argument(
        "--target-lai and --target-ground-cover choose a row layout's plant spacing: not with --positions");
  if (o.rows.plant_spacing)
    throw std::invalid_argument(
        "--target-lai and --target-ground-cover choose the plant spacing: leave out --plant-spacing");
  if (t.lai && t.ground_cover)
    throw std::invalid_argument("--target-lai and --target-ground-cover: give one of them");
  if (t.lai && t.error)
    throw std::invalid_argument(
        "--target-error: the standard error of --target-ground-cover's estimates; --target-lai's leaf area "
        "is "
        "exact (leave it out)");
}

void check_plan_fits(const StandPlan& plan, std::size_t plants) {
  GrowRequest first = plan.request;
  if (first.plants.empty()) {
    RowLayout one = plan.layout;
    one.rows = one.per_row = 1;
    first.plants = row_layout(one);
  }
  first.plants.resize(std::min<std::size_t>(first.plants.size(), 1));
  if (!first.plants.empty() && plants > 0) check_stand_fits(first, plants);
}

void place_plan(StandPlan& plan, const StandOptions& o) {
  if (o.positions.empty()) {
    // grow_stand grows the first plant and refuses a stand of its copies that would not fit,
    // before the others grow; only where the placements alone would take much of the memory is
    // that said before they are made, from a first plant grown here (a plant of 100,000 steps
    // took 20 s to grow, and was grown twice).
    const std::size_t n =
        static_cast<std::size_t>(plan.layout.rows) * static_cast<std::size_t>(plan.layout.per_row);
    if (const std::size_t room = available_memory();
        room && static_cast<double>(n) * sizeof(PlantPlacement) > static_cast<double>(room) / 16)
      check_plan_fits(plan, n);
    plan.request.plants = row_layout(plan.layout);
  }
  check_target(o);
  // The spacing is the target's choice, whatever gave the one it starts from.
  if (o.target.set())
    for (auto& [name, source] : plan.layout_sources)
      if (name == "plant_spacing") source = o.target.lai ? "--target-lai" : "--target-ground-cover";
}

void describe_run(StandReport& rep, const StandOptions& o, const std::set<std::string>& formats,
                  const StandPlan& plan) {
  const RowLayout& layout = plan.layout;
  nlohmann::ordered_json config;
  config["grammar"] = o.grammar;
  config["out"] = o.out;
  config["steps"] = o.steps ? nlohmann::ordered_json(*o.steps) : nlohmann::ordered_json(nullptr);
  config["set"] = o.set;
  config["lod"] = o.lod;
  config["formats"] = std::vector<std::string>(formats.begin(), formats.end());
  config["glb_instancing"] = o.glb_instancing;
  config["glb_compact"] = o.glb_compact;
  config["max_modules"] = o.max_modules;
  config["level"] = o.detect.level;
  config["clearance"] = o.detect.clearance;
  config["collide"] = o.detect.collide;
  config["backend"] = o.detect.backend;
  config["threads"] = o.detect.threads;
  config["max_device_memory"] = o.detect.max_device_memory.empty()
                                    ? nlohmann::ordered_json(nullptr)
                                    : nlohmann::ordered_json(o.detect.max_device_memory);
  config["resolve"] = o.resolve.config_json();
  if (!o.positions.empty()) {
    config["layout"] = {{"positions", o.positions}};
    if (o.any_grammar_path) config["layout"]["any_grammar_path"] = true;
  } else {
    nlohmann::ordered_json sources;
    for (const auto& [field, source] : plan.layout_sources) sources[field] = source;
    config["layout"] = {{"rows", layout.rows},
                        {"per_row", layout.per_row},
                        {"row_spacing", layout.row_spacing},
                        {"plant_spacing", layout.plant_spacing},
                        {"double_rows", layout.double_rows ? nlohmann::ordered_json(*layout.double_rows)
                                                           : nlohmann::ordered_json(nullptr)},
                        {"jitter", layout.jitter},
                        {"random_rotation", layout.random_rotation},
                        {"seed", layout.seed},
                        {"sources", sources}};  // per field: command line, grammar or default
  }
  rep.config = config;
  rep.grammar = plan.grammar.name.empty() ? o.grammar : plan.grammar.name;
  rep.seed = o.positions.empty() ? nlohmann::ordered_json(layout.seed) : nlohmann::ordered_json(nullptr);
}

namespace {

/// What the report needs besides the files (check_stand).
struct StandChecks {
  std::optional<Contacts> after;  // the detection after resolution (none without one)
  double detect_s = 0, detect_peak_gb = 0;
  std::string backend;
  nlohmann::ordered_json device;
  StandCounts counts;
  nlohmann::ordered_json leaf_angles;
};

/// The stand's detection after resolution (where `resolved`), the backend's name and device, then
/// the counts and leaf angles, on `threads` (0: all). Where `ends_process`, the backend (and the
/// context of `gpu`, its device: -1 none) is let go as soon as the detection is made.
StandChecks check_stand(const Stand& stand, PrototypeLibrary& lib, const DetectRequest& dreq, bool resolved,
                        int threads, bool ends_process, [[maybe_unused]] int gpu,
                        std::unique_ptr<DetectionBackend> backend) {
  const ThreadLimit thread_limit(threads);  // the export's default team is bounded on its own thread
  StandChecks c;
  if (resolved) {
    const auto t = std::chrono::steady_clock::now();
    StagePeak peak;
    c.after = backend->detect(stand, dreq);
    c.detect_s = seconds_since(t);
    c.detect_peak_gb = peak.gb();
  }
  c.backend = backend->name();
  c.device = backend->device();
  if (ends_process) {
#ifdef CANOPY_HAVE_CUDA
    if (gpu >= 0) {
      cuda::select_device(gpu);  // the backend's buffers are freed on its device
      backend.reset();
      cuda::reset_device(gpu);
    }
#endif
    backend.reset();
  }
  c.counts = stand_counts(stand, lib);  // every organ's mesh walked: once for the file and the summary
  c.leaf_angles = leaf_angles_json(leaf_angles(leaf_angle_sums(stand, lib)));
  return c;
}

}  // namespace

StandOutcome run_stand(StandOptions o, bool print, std::function<void(const ResolveProgress&)> progress,
                       Stand* keep) {
  const auto t_start = std::chrono::steady_clock::now();
  const ThreadLimit thread_limit(o.detect.threads);
  const std::set<std::string> formats = parse_formats(o.formats);
  const GlbForm glb = glb_form(o);
  StandPlan plan = plan_stand(o);
  if (print) print_notes(plan.grammar.notes);
  const DetectRequest dreq = o.detect.request();  // bad options fail before any work
  // A GPU's start (its driver and context, 0.2-0.4 s) runs on a thread of its own while the stand
  // grows; without a GPU's device files, or with --backend cpu, the backend is made at once (so
  // --backend cuda on a machine without a GPU is refused before any work).
  std::string backend_note;
  std::unique_ptr<DetectionBackend> backend;
  std::future<std::unique_ptr<DetectionBackend>> starting;
  if (o.detect.backend != "cpu" && gpu_device_files())
    starting = std::async(std::launch::async, [name = o.detect.backend, &backend_note] {
      return make_backend(name, backend_note);
    });
  else backend = make_backend(o.detect.backend, backend_note);
  // The staging folder beside the output (dead runs' leftovers removed first): the files go
  // there and the folder is swapped in once they are complete; a failed or interrupted run
  // removes it, so the output folder is as it was (none made when it had none).
  refuse_output_over_inputs(plan_inputs(plan, o), o.out);  // before the folder is touched
  OutputSet files(o.out, stand_folder_files(), kStandFolderMarker);
  GrowRequest& req = plan.request;
  place_plan(plan, o);
  const auto t_grow = std::chrono::steady_clock::now();
  GrowTimings gt;
  StagePeak grow_peak;
  Stand stand = grow_stand(req, &gt);
  StandReport rep;
  rep.peak_memory["generate"] = grow_peak.gb();
  rep.timings["generate"] = seconds_since(t_grow);
  // Start-up: before growing (options, the grammar, the output folder) and whatever of the
  // backend's start growing did not cover.
  const auto t_wait = std::chrono::steady_clock::now();
  if (starting.valid()) backend = starting.get();
  rep.timings["startup"] = std::chrono::duration<double>(t_grow - t_start).count() + seconds_since(t_wait);
  // Refused before the work: a compact glb's plant with too many organs, a glb past 4 GiB.
  PrototypeLibrary lib;
  if (glb.compact && formats.count("glb")) check_glb_compact(ExportScope::whole(stand));
  if (!glb.compact && !glb.instancing && formats.count("glb")) check_glb_fits(stand, lib);
  std::optional<SpacingChoice> target;
  if (o.target.set()) {
    const auto t_target = std::chrono::steady_clock::now();
    target = reach_target(stand, plan.layout, o.target);
    rep.timings["target"] = seconds_since(t_target);
  }

  // Detection at the level asked for; contacts.csv and contacts_before come from it.
  const auto t_detect = std::chrono::steady_clock::now();
  StagePeak detect_peak;
  const Contacts contacts = backend->detect(stand, dreq);
  rep.timings["detect"] = seconds_since(t_detect);
  rep.peak_memory["detect"] = detect_peak.gb();
  rep.timings["detect_build"] = contacts.build_s;  // parts of "detect": the bounding volumes,
  rep.timings["detect_upload"] = contacts.load_s;  // the stand's trip to the device
  const std::string first_backend = backend->name();
  rep.contacts_before = counts_json(contacts);

  // Resolution; detection from scratch at the same level for contacts_after follows it.
  std::optional<ResolveResult> resolved;
  if (!o.resolve.no_resolve) {
    const auto t_resolve = std::chrono::steady_clock::now();
    StagePeak resolve_peak;
    const ResolveConfig rc = o.resolve.config();
    DetectRequest at = dreq;
    at.level = rc.level;
    // Resolution starts from its own level's contacts, on a tree the backend keeps.
    const Contacts start = dreq.level == rc.level ? contacts : backend->detect(stand, at);
    ResolveOptions ro = o.resolve;
    ro.progress_lines = print;
    resolved = run_resolution(stand, *backend, dreq, ro, start, progress);
    rep.timings["resolve"] = seconds_since(t_resolve);
    rep.peak_memory["resolve"] = resolve_peak.gb();
    rep.resolution = resolution_json(*resolved);
  } else {
    rep.resolution = resolution_not_run_json(contacts);
  }

  // What the report needs besides the files is made on a thread of its own while they are
  // written, each part only reading the stand: the detection after resolution, the counts and
  // leaf angles (every organ's mesh walked). The export mostly waits for the disk (10,000
  // plants on 2 cores: 9.3 s, 7.9 of them in writes, against 0.52 s for the detection after).
  // A process that ends after this run then frees the backend, and a GPU's context, there too,
  // instead of when the process ends (tools/process_end.hpp).
#ifdef CANOPY_HAVE_CUDA
  const int gpu = backend->name() == "cuda" ? cuda::current_device() : -1;
#else
  const int gpu = -1;
#endif
  StagePeak export_peak;
  std::future<StandChecks> checking = std::async(std::launch::async, [&, b = std::move(backend)]() mutable {
    return check_stand(stand, lib, dreq, resolved.has_value(), o.detect.threads, o.ends_process, gpu,
                       std::move(b));
  });
  // --threads N bounds every computing phase to N threads: then the two do not overlap.
  if (o.detect.threads > 0) checking.wait();
  const auto t_export = std::chrono::steady_clock::now();
  write_stand_files(stand, lib, formats, glb, files);
  write_contacts_csv(stand, contacts, files.open("contacts.csv"));
  rep.timings["export"] = seconds_since(t_export);
  StandChecks checked = checking.get();
  const Contacts& after = checked.after ? *checked.after : contacts;  // unresolved: as first found
  write_contacts_csv(stand, after, files.open("contacts_after.csv"));
  if (resolved) {
    rep.timings["detect_after"] = checked.detect_s;
    rep.peak_memory["detect_after"] = checked.detect_peak_gb;
  }
  rep.peak_memory["export"] = export_peak.gb();
  rep.contacts_after = counts_json(after);
  rep.backend = checked.backend;  // what ran to the end (auto may have fallen back)
  rep.device = checked.device;
  rep.backend_choice = backend_note;
  rep.peak_memory["total"] = static_cast<double>(process_peak_bytes()) / 1e9;  // the process's, so far
  // The export's bytes are made on all threads while a writer thread writes the previous ones:
  // formatting is the time it did not wait for writes, writing the time spent in them.
  const WriteTimes written = files.times();
  rep.timings["export_format"] = std::max(0.0, rep.timings["export"] - written.waited_s);
  rep.timings["export_write"] = written.busy_s;
  describe_run(rep, o, formats, plan);
  if (target) rep.config["target"] = target_json(o.target, *target);
  rep.leaf_angles = std::move(checked.leaf_angles);
  rep.timings["total"] = seconds_since(t_start);
  const StandCounts& counts = checked.counts;
  nlohmann::ordered_json report = report_json(counts, rep);
  files.open("report.json").write(json_text(report, 2) + "\n");
  if (o.more_files) o.more_files(stand, report, files);
  const auto t_commit = std::chrono::steady_clock::now();
  const StagedFolder::Committed committed = files.commit_all();
  const double commit_s = seconds_since(t_commit);
  if (print) {
    print_folder_changes(files.folder(), committed);
    if (target)
      fmt::print("target {} {}: plant spacing {} m ({} {:.4f}{})\n", o.target.lai ? "LAI" : "ground cover",
                 o.target.lai ? *o.target.lai : *o.target.ground_cover, target->plant_spacing,
                 o.target.lai ? "LAI" : "ground cover", target->reached,
                 o.target.lai ? std::string() : fmt::format(" +- {:.4f}", target->standard_error));
    print_summary(counts, rep, o.out);
    if (o.positions.empty()) fmt::print("{}\n", layout_line(plan.layout, plan.layout_sources));
    print_contacts_table(contacts, backend_note);
    if (rep.backend != first_backend)
      fmt::print("backend: the run ended on {}: {}\n", rep.backend, rep.device.get<std::string>());
    if (resolved) print_resolution(*resolved);
  }
  StandOutcome out;
  out.report = std::move(report);
  out.notes = plan.grammar.notes;
  out.contacts_before = contacts.pairs.size();
  out.contacts_after = after.pairs.size();
  out.export_bytes = written.bytes;
  out.commit_s = commit_s;
  if (keep) *keep = std::move(stand);
  else if (o.ends_process) leave_to_process_end(std::move(stand));
  return out;
}

}  // namespace canopy::cli
