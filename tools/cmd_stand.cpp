// canopy stand: grow a stand from a grammar and a layout and write its files.
#include "geometry/export.hpp"
#include "geometry/layout.hpp"
#include "lsystem/grow.hpp"
#include "tools/cli_common.hpp"
#include "tools/detect_options.hpp"
#include "tools/report.hpp"
#include "tools/resolve_options.hpp"

#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <set>

namespace canopy::cli {
namespace {

struct StandOptions {
  std::string grammar;
  std::string out = "out";
  std::optional<int> steps;
  std::vector<std::string> set;
  int lod = kDefaultLod;
  std::string formats = "glb";
  bool glb_instancing = false;
  std::size_t max_modules = kDefaultMaxModules;
  StandSpec rows;               // row options given on the command line
  bool random_rotation = false;  // folded into `rows` once parsed
  std::string positions;
  DetectOptions detect;
  ResolveOptions resolve;
};

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

bool any_row_option(const StandSpec& s) {
  return s.rows || s.per_row || s.row_spacing || s.plant_spacing || s.double_rows || s.jitter || s.random_rotation || s.seed;
}

/// A row layout from a stand entry (the grammar's or the command line's); unset keys take
/// DESIGN.md's defaults: 1 x 1 plants, 1.0 m rows, 0.4 m in the row, no jitter, no rotation, seed 1.
RowLayout to_row_layout(const StandSpec& s) {
  RowLayout l;
  l.rows = s.rows.value_or(1);
  l.per_row = s.per_row.value_or(1);
  l.row_spacing = s.row_spacing.value_or(1.0);
  l.plant_spacing = s.plant_spacing.value_or(0.4);
  l.double_rows = s.double_rows;
  l.jitter = s.jitter.value_or(0);
  l.random_rotation = s.random_rotation.value_or(false);
  l.seed = s.seed.value_or(1);
  return l;
}

Command add_stand(CLI::App& root) {
  auto o = std::make_shared<StandOptions>();
  CLI::App* app = root.add_subcommand("stand", "Grow a stand of plants from a grammar and write its files");
  app->add_option("GRAMMAR", o->grammar, "Grammar file (YAML)")->required();
  app->add_option("-o,--out", o->out, "Output folder (created if missing; default out)");
  app->add_option("--steps", o->steps, "Derivation steps for every plant (default: the grammar's)")->check(CLI::NonNegativeNumber);
  app->add_option("--set", o->set, "Override a constant: NAME=VALUE (repeatable)");
  app->add_option("--lod", o->lod, "Level of detail of prototype meshes, 1 (coarse) to 16 (default 2)")->check(CLI::Range(1, kMaxLod));
  app->add_option("--formats", o->formats, "Mesh formats to write, comma separated: glb,obj,ply (default glb)");
  app->add_flag("--glb-instancing", o->glb_instancing,
                "Write stand.glb with one shared mesh per prototype drawn per organ (EXT_mesh_gpu_instancing): "
                "about 20 times smaller; organ ids become a per-instance _ORGAN attribute");
  app->add_option("--max-modules", o->max_modules, "Module cap per plant derivation")->check(CLI::PositiveNumber);
  o->detect.add_to(*app);
  o->resolve.add_to(*app);
  auto* layout = app->add_option_group("layout", "Rows (any of these replaces the grammar's stand entry) or a positions file");
  layout->add_option("--rows", o->rows.rows, "Number of rows (along +X, spaced along +Y)")->check(CLI::PositiveNumber);
  layout->add_option("--per-row", o->rows.per_row, "Plants per row")->check(CLI::PositiveNumber);
  layout->add_option("--row-spacing", o->rows.row_spacing, "Metres between rows (default 1.0)")->check(CLI::NonNegativeNumber);
  layout->add_option("--plant-spacing", o->rows.plant_spacing, "Metres between plants in a row (default 0.4)")->check(CLI::NonNegativeNumber);
  layout->add_option("--double-rows", o->rows.double_rows, "Rows in pairs GAP metres apart; pairs --row-spacing apart")->check(CLI::NonNegativeNumber);
  layout->add_option("--jitter", o->rows.jitter, "Radius in metres of a uniform disc around each position")->check(CLI::NonNegativeNumber);
  layout->add_flag("--random-rotation", o->random_rotation, "Turn each plant by a random angle about Z");
  layout->add_option("--seed", o->rows.seed, "Stand seed: plant seeds, jitter and rotations derive from it (default 1)");
  layout->add_option("--positions", o->positions, "CSV with columns x,y,rotation,seed and optional grammar,steps");
  return {app, [o]() {
            const auto t_start = std::chrono::steady_clock::now();
            std::set<std::string> formats;
            for (std::size_t i = 0; i <= o->formats.size();) {
              std::size_t j = o->formats.find(',', i);
              if (j == std::string::npos) j = o->formats.size();
              const std::string f = o->formats.substr(i, j - i);
              if (f != "glb" && f != "obj" && f != "ply")
                throw std::invalid_argument(fmt::format("--formats: unknown format '{}' (expected glb, obj, ply)", f));
              formats.insert(f);
              i = j + 1;
            }
            if (o->random_rotation) o->rows.random_rotation = true;
            if (!o->positions.empty() && any_row_option(o->rows))
              throw std::invalid_argument("--positions cannot be combined with row options");
            const DetectRequest dreq = o->detect.request();  // bad options fail before any work
            std::string backend_note;
            auto backend = make_backend(o->detect.backend, backend_note);
            prepare_output_dir(o->out);

            GrowRequest req;
            req.grammar = o->grammar;
            for (const auto& s : o->set) req.load.overrides.push_back(parse_override(s));
            req.steps = o->steps;
            req.lod = o->lod;
            req.threads = o->detect.threads;
            req.max_modules = o->max_modules;
            const Grammar g = load_grammar(o->grammar, req.load);
            bool from_grammar = false;
            RowLayout layout;
            if (!o->positions.empty()) {
              req.plants = read_positions(o->positions);
              req.relative_to = std::filesystem::path(o->positions).parent_path().string();
            } else {
              // Command-line row options replace the grammar's stand entry as a whole.
              from_grammar = !any_row_option(o->rows) && g.stand.has_value();
              layout = to_row_layout(from_grammar ? *g.stand : o->rows);
              // Say so before trying when the stand cannot fit: probe with its first plant.
              RowLayout first = layout;
              first.rows = first.per_row = 1;
              req.plants = row_layout(first);
              check_stand_fits(req, static_cast<std::size_t>(layout.rows) * static_cast<std::size_t>(layout.per_row));
              req.plants = row_layout(layout);
            }
            const auto t_grow = std::chrono::steady_clock::now();
            GrowTimings gt;
            Stand stand = grow_stand(req, &gt);
            StandReport rep;
            rep.timings["generate"] = seconds_since(t_grow);

            // Detection at the level asked for; contacts.csv and contacts_before come from it.
            const auto t_detect = std::chrono::steady_clock::now();
            const Contacts contacts = backend->detect(stand, dreq);
            rep.timings["detect"] = seconds_since(t_detect);
            rep.backend = backend->name();
            rep.device = backend->device();
            rep.contacts_before = counts_json(contacts);

            // Resolution, then detection from scratch at the same level for contacts_after.
            Contacts after = contacts;
            std::optional<ResolveResult> resolved;
            if (!o->resolve.no_resolve) {
              const auto t_resolve = std::chrono::steady_clock::now();
              const ResolveConfig rc = o->resolve.config();
              DetectRequest at = dreq;
              at.level = rc.level;
              // Resolution starts from its own level's contacts, on a tree the backend keeps.
              const Contacts start = dreq.level == rc.level ? contacts : backend->detect(stand, at);
              resolved = run_resolution(stand, *backend, dreq, o->resolve, start);
              rep.timings["resolve"] = seconds_since(t_resolve);
              const auto t_check = std::chrono::steady_clock::now();
              after = backend->detect(stand, dreq);
              rep.timings["detect_after"] = seconds_since(t_check);
              rep.resolution = resolution_json(*resolved);
            }
            rep.contacts_after = counts_json(after);

            PrototypeLibrary lib;
            OutputSet files(o->out);
            const auto t_export = std::chrono::steady_clock::now();
            if (formats.count("glb")) {
              if (o->glb_instancing) write_glb_instanced(stand, lib, files.open("stand.glb"));
              else write_glb(stand, lib, files.open("stand.glb"));
            }
            if (formats.count("obj")) write_obj(stand, lib, files.open("stand.obj"), files.open("stand.mtl"), "stand.mtl");
            if (formats.count("ply")) write_ply(stand, lib, files.open("stand.ply"));
            write_organs_csv(stand, lib, files.open("organs.csv"));
            write_plants_csv(stand, files.open("plants.csv"));
            files.open("contacts.csv").write(contacts_csv(contacts));
            files.open("contacts_after.csv").write(contacts_csv(after));
            rep.timings["export"] = seconds_since(t_export);

            nlohmann::ordered_json config;
            config["grammar"] = o->grammar;
            config["steps"] = o->steps ? nlohmann::ordered_json(*o->steps) : nlohmann::ordered_json(nullptr);
            config["set"] = o->set;
            config["lod"] = o->lod;
            config["formats"] = std::vector<std::string>(formats.begin(), formats.end());
            config["glb_instancing"] = o->glb_instancing;
            config["max_modules"] = o->max_modules;
            config["level"] = o->detect.level;
            config["clearance"] = o->detect.clearance;
            config["collide"] = o->detect.collide;
            config["backend"] = o->detect.backend;
            config["threads"] = o->detect.threads;
            config["resolve"] = o->resolve.config_json();
            if (!o->positions.empty()) {
              config["layout"] = {{"positions", o->positions}};
            } else {
              config["layout"] = {{"source", from_grammar ? "grammar" : "command line"},
                                  {"rows", layout.rows},
                                  {"per_row", layout.per_row},
                                  {"row_spacing", layout.row_spacing},
                                  {"plant_spacing", layout.plant_spacing},
                                  {"double_rows", layout.double_rows ? nlohmann::ordered_json(*layout.double_rows) : nlohmann::ordered_json(nullptr)},
                                  {"jitter", layout.jitter},
                                  {"random_rotation", layout.random_rotation},
                                  {"seed", layout.seed}};
            }
            rep.config = config;
            rep.grammar = g.name.empty() ? o->grammar : g.name;
            rep.seed = o->positions.empty() ? nlohmann::ordered_json(layout.seed) : nlohmann::ordered_json(nullptr);
            rep.timings["total"] = seconds_since(t_start);
            write_report(stand, lib, rep, files.open("report.json"));
            files.commit_all();
            print_summary(stand, lib, rep, o->out);
            print_contacts_table(contacts, backend_note);
            if (resolved) print_resolution(*resolved);
            return 0;
          }};
}

}  // namespace canopy::cli
