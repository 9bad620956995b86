#pragma once
/// `canopy light` as a library call, shared by the command line, the Python module and sweeps:
/// the options, the tile (the layout's lattice, --tile, or the stand's footprint), the run, and
/// light.json / light.csv.
#include "geometry/layout.hpp"
#include "geometry/stand.hpp"
#include "tools/stand_run.hpp"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#ifdef CANOPY_HAVE_LIGHT
#include "light/light.hpp"
#endif

namespace canopy::cli {

/// Every option of `canopy light` (the command line's names); `stand` holds the options of
/// `canopy stand` used when the source is a grammar.
struct LightOptions {
  std::string source;
  std::vector<std::string> suns;  // "ELEVATION,AZIMUTH"
  std::optional<double> latitude;
  std::optional<int> day;
  std::string hours;  // "8,10,12": local solar times
  std::string sky = "soc";
  int sky_directions = 46;
  std::string tile;  // "XMIN,YMIN,XMAX,YMAX"
  bool no_periodic = false;
  double error = 0.002;
  std::optional<double> plant_error;
  std::optional<double> rays_per_m2;
  double layer = 0.1;
  std::uint64_t ray_seed = 1;
  std::string caster = "auto";  // auto, trace or raster (light::Caster)
  int threads = 0;
  StandOptions stand;
};

/// `canopy light`'s arguments and options registered on `app` (the subcommand, or an app of the
/// Python module's own).
std::shared_ptr<LightOptions> register_light(CLI::App& app);
/// After parsing: the thread count taken from --threads, and a folder SOURCE's refusal of the
/// options that would grow, detect or resolve a stand.
void check_light_command(const CLI::App& app, LightOptions& o);

/// The sun positions asked for: each --sun, then one per --hours entry from --latitude and --day
/// (the hour kept beside it; NaN for --sun).
struct SunSpec {
  double elevation_deg = 90, azimuth_deg = 0, hour = 0;
  bool from_hours = false;
};
std::vector<SunSpec> parse_suns(const LightOptions& o);

/// "XMIN,YMIN,XMAX,YMAX" in metres; throws std::invalid_argument naming --tile.
std::array<double, 4> parse_tile(const std::string& text);
/// The lattice a row layout repeats (world metres): each plant's cell, plant spacing by row
/// spacing, the first plant's centred on the origin; double rows repeat per pair of rows.
std::array<double, 4> lattice_tile(const RowLayout& layout);
/// The row layout a folder written by canopy stand was made with (report.json's config), or
/// nothing for a positions file or a folder without report.json (Stand.export writes none).
std::optional<RowLayout> folder_layout(const std::string& dir);

struct LightOutcome {
  nlohmann::ordered_json json;  // light.json as written
  std::string csv;              // light.csv as written
  std::string dir;
  std::vector<std::string> notes;  // from a grammar: its notes (Grammar::notes)
};

/// Runs `canopy light` with `o`: writes light.json and light.csv (from a grammar, with the
/// stand's own files) and prints a summary when `print`.
LightOutcome run_light(LightOptions o, bool print = true);

#ifdef CANOPY_HAVE_LIGHT
/// What light_config chose beside the configuration: the beams as given, and the tile in world
/// coordinates as given or made (light.json echoes it; the configuration's is relative to the
/// stand's origin, which does not round-trip: -1 came back as -0.9999999999999999).
struct LightSetup {
  std::vector<SunSpec> suns;
  std::array<double, 4> tile{};
};
/// The light configuration of `o` for `stand`; `layout`, when known, gives the lattice tile.
light::LightConfig light_config(const LightOptions& o, const Stand& stand,
                                const std::optional<RowLayout>& layout, LightSetup& setup);
/// light.json's content and light.csv's text.
nlohmann::ordered_json light_json(const light::LightResult& r, const Stand& stand, const LightOptions& o,
                                  const LightSetup& setup);
std::string light_csv(const light::LightResult& r, const Stand& stand);
#endif

}  // namespace canopy::cli
