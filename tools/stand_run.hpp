#pragma once
/// `canopy stand` as a library call: grow, detect, resolve, export and report, shared by the
/// command line and the Python module (same code, same files).
#include "resolution/resolve.hpp"
#include "geometry/atomic_file.hpp"
#include "geometry/export.hpp"
#include "geometry/prototype.hpp"
#include "lsystem/grammar.hpp"
#include "lsystem/grow.hpp"
#include "tools/detect_options.hpp"
#include "tools/report.hpp"
#include "tools/resolve_options.hpp"
#include "tools/stand_target.hpp"

#include <functional>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace canopy::cli {

/// Every option of `canopy stand` (the command line's names).
struct StandOptions {
  std::string grammar;
  std::string out = "out";
  std::optional<int> steps;
  std::vector<std::string> set;
  int lod = kDefaultLod;
  std::string formats = "glb";
  bool glb_instancing = false;
  bool glb_compact = false;
  std::size_t max_modules = kDefaultMaxModules;
  StandSpec rows;                   // row options given on the command line
  bool random_rotation = false;     // folded into `rows` once parsed
  bool no_random_rotation = false;  // the same, to turn off the grammar entry's rotation
  std::string positions;
  bool any_grammar_path = false;  // a positions file's grammar cells may name any file
  DetectOptions detect;
  ResolveOptions resolve;
  TargetOptions target;  // --target-lai / --target-ground-cover choose the plant spacing
  /// Set by a caller whose process ends right after the run (canopy stand, bench_stand's run of
  /// one size): the backend is freed (and a GPU's context destroyed) while the files are written,
  /// and the stand is left to the process's end rather than freed (tools/process_end.hpp).
  bool ends_process = false;
  /// Called once the stand's own files are made and report.json's text is known, before any is
  /// put in place: more files for the same folder (canopy light's light.json and light.csv, from
  /// the stand as resolved and the report as written). What it throws leaves the folder as it was.
  std::function<void(const Stand&, const nlohmann::ordered_json& report, OutputSet& files)> more_files;
};

struct StandOutcome {
  nlohmann::ordered_json report;  // report.json as written (its timings_s per stage)
  std::size_t contacts_before = 0, contacts_after = 0;
  std::uint64_t export_bytes = 0;  // the mesh and table files (report.json aside)
  double commit_s = 0;             // the files closed and put in place, after report.json
  std::vector<std::string> notes;  // the grammar's (Grammar::notes), printed when the run prints
};

/// What a stand is grown from: the grammar, the grow request (placements filled in for a
/// positions file; row layouts are placed by the caller with row_layout(layout)), the layout
/// (the command line's row options over the grammar's stand entry, field by field) and where
/// each of its values came from.
struct StandPlan {
  GrowRequest request;
  Grammar grammar;
  RowLayout layout;
  LayoutSources layout_sources;  // empty with a positions file
};
StandPlan plan_stand(StandOptions& o);
/// Throws std::invalid_argument when the target options (--target-lai, --target-ground-cover,
/// --target-error) cannot apply to `o`; nothing to check without them.
void check_target(const StandOptions& o);
/// Throws before growing when `plants` plants like the plan's first would not fit in memory.
void check_plan_fits(const StandPlan& plan, std::size_t plants);
/// Before growing: a row layout's plants placed in plan.request (said first when they cannot fit
/// in memory; a positions file's are there already), and a target's options checked.
void place_plan(StandPlan& plan, const StandOptions& o);
/// report.json's "config" (every option echoed), "grammar" and "seed".
void describe_run(StandReport& rep, const StandOptions& o, const std::set<std::string>& formats,
                  const StandPlan& plan);

/// How stand.glb is written: a mesh per plant (the default), instanced, or compact.
struct GlbForm {
  bool instancing = false;
  bool compact = false;
  GlbCompactConfig compact_config;
};
/// The form the options ask for; the compact glb's step stays below half the resolution
/// clearance (half the default clearance when it is 0). Throws when both forms are asked for.
GlbForm glb_form(const StandOptions& o);
/// The names a caller gives the glb forms and the format list, in its refusals.
struct OptionNames {
  const char *instancing, *compact, *formats;
};
/// Refuses a glb form (instancing or compact) when `formats` writes no glb.
void check_glb_written(bool instancing, bool compact, const std::string& formats, const OptionNames& names);
GlbForm glb_form(bool instancing, bool compact, double resolve_clearance);

/// "glb,obj" -> {glb, obj}; throws std::invalid_argument on an unknown format.
std::set<std::string> parse_formats(const std::string& list);
/// Opens a file of the stand folder by name as a ChunkWriter (one process: over an OutputSet's
/// AtomicFile; tiles: a file every rank writes with MPI-IO).
using OpenChunks = std::function<ChunkWriter&(const std::string& name)>;
/// The mesh and table files of the scope's plants as `canopy stand` writes them (not the
/// contacts or the report): stand.{glb,obj+mtl,ply} for `formats`, organs.csv, plants.csv.
/// stand.glb compact when `glb.compact` (instancing is written by write_stand_files below only).
void write_stand_files(const ExportScope& scope, PrototypeLibrary& lib, const std::set<std::string>& formats,
                       const OpenChunks& open, const GlbForm& glb = {});
/// The same for a whole stand in one process, stand.glb in the form `glb`.
void write_stand_files(const Stand& stand, PrototypeLibrary& lib, const std::set<std::string>& formats,
                       const GlbForm& glb, OutputSet& files);

/// The files of a stand folder that a run replaces as a set (StagedFolder's `replaces`): the
/// meshes, tables and report canopy stand writes, and light.csv, light.json (computed from a
/// stand, so they go with it). Everything else in the folder is kept. Every stand writer (the
/// command line, tiled runs, the Python module) replaces these.
const std::vector<std::string>& stand_folder_files();
/// The file every stand folder holds: a folder without it holds no earlier stand, and files of
/// the names above there are the user's (kept unless a run writes them again).
inline constexpr const char* kStandFolderMarker = "organs.csv";
/// Throws std::invalid_argument when `path`, given with `option` for a file a command writes
/// (`detect --csv`, `render -o`), names one of stand_folder_files() in a folder that holds a stand:
/// writing it would replace the stand's own table (or the contacts its report counts).
void refuse_stand_file(const std::string& option, const std::string& path);
/// Throws std::invalid_argument, before any work, where a file to write (`option`'s `path`,
/// a `kind` such as "PNG" or "CSV") cannot be: a folder, or in a folder that does not exist.
void refuse_file_place(const std::string& option, const std::string& path, const std::string& kind);
/// A file this run reads (`what`: "the grammar", "the positions file") and its path.
struct RunInput {
  std::string what, path;
};
/// The files a stand plan reads: the grammar, the positions file and the grammars it names.
std::vector<RunInput> plan_inputs(const StandPlan& plan, const StandOptions& o);
/// Throws std::invalid_argument when an input is the same file (through links) as one the run
/// writes or replaces: `out_file` itself, or, for a stand folder `out_dir`, any of
/// stand_folder_files() in it. Its data would be lost (`--positions DIR/plants.csv -o DIR` took
/// the stand's table for the user's positions).
void refuse_output_over_inputs(const std::vector<RunInput>& inputs, const std::string& out_dir,
                               const std::string& out_file = {});
/// Says on standard output which files of the earlier stand the swap dropped (a mesh format not
/// asked for this time, light tables) and which dead runs' leftovers were removed, and on
/// standard error what was kept against the plan (nothing when all went as planned).
void print_folder_changes(const StagedFolder& folder, const StagedFolder::Committed& committed);

/// Runs `canopy stand` with `o`: writes the files into o.out, prints the summary when `print`.
/// `progress`, when set, is called once per resolution round (instead of the terminal line).
/// `keep`, when set, receives the stand as exported.
StandOutcome run_stand(StandOptions o, bool print = true,
                       std::function<void(const ResolveProgress&)> progress = {}, Stand* keep = nullptr);

}  // namespace canopy::cli
