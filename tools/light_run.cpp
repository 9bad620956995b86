// canopy light's run: the stand (a folder or a grammar), the tile, the light, the files.
#include "tools/light_run.hpp"
#include "tools/folder_counts.hpp"
#include "geometry/input_file.hpp"
#include "tools/json_text.hpp"

#include "tools/light_device.hpp"

#include "geometry/export.hpp"
#include "geometry/thread_limit.hpp"
#include "tools/cli_common.hpp"
#include "tools/sweep_spec.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace canopy::cli {

std::vector<SunSpec> parse_suns(const LightOptions& o) {
  std::vector<SunSpec> out;
  // One beam a direction, as --hours takes an hour once (a second was traced again and counted as
  // a sun of its own); azimuths a turn apart are one direction (60,180 and 60,-180).
  const auto turn = [](double az) { return std::fmod(std::fmod(az, 360.0) + 360.0, 360.0); };
  for (const std::string& s : o.suns) {
    const auto [e, a] = number_pair("--sun", s);
    for (const SunSpec& y : out)
      if (y.elevation_deg == e && turn(y.azimuth_deg) == turn(a))
        throw std::invalid_argument(fmt::format("--sun {}: given twice; give each sun once", s));
    SunSpec x;
    x.elevation_deg = e, x.azimuth_deg = a;
    out.push_back(x);
  }
  const bool solar = o.latitude || o.day || !o.hours.empty();
  if (solar) {
    if (!o.latitude || !o.day || o.hours.empty())
      throw std::invalid_argument("--latitude, --day and --hours go together");
    for (double h : parse_number_list("--hours", o.hours, 0, false)) {
#ifdef CANOPY_HAVE_LIGHT
      const light::SunPosition p = light::solar_position(*o.latitude, *o.day, h);
      if (!(p.elevation_deg > 0))
        throw std::invalid_argument(
            fmt::format("--hours: at {} h the sun is {:.1f} degrees below the horizon (latitude {}, day {})",
                        h, -p.elevation_deg, *o.latitude, *o.day));
      SunSpec x;
      // Azimuth in [0, 360) with no negative zero (light.json wrote -0.0 for a noon sun in the
      // north, and hours 0 and 24 gave azimuths 0 and 360).
      double azimuth = std::fmod(p.azimuth_deg, 360.0);
      if (azimuth < 0) azimuth += 360.0;
      if (azimuth == 0 || azimuth >= 360.0) azimuth = 0.0;
      x.elevation_deg = p.elevation_deg, x.azimuth_deg = azimuth, x.hour = h, x.from_hours = true;
      out.push_back(x);
#else
      (void)h;  // no ray caster: run_light refuses before any beam is used
#endif
    }
  }
  return out;
}

std::array<double, 4> parse_tile(const std::string& text) {
  std::array<double, 4> t{};
  std::size_t at = 0;
  for (int k = 0; k < 4; ++k) {
    std::size_t used = 0;
    const std::string rest = text.substr(std::min(at, text.size()));
    t[static_cast<std::size_t>(k)] = leading_number(rest, used);
    const bool last = k == 3;
    if (used == 0 || !std::isfinite(t[static_cast<std::size_t>(k)]) ||
        (last ? used != rest.size() : (used >= rest.size() || rest[used] != ',')))
      throw std::invalid_argument(fmt::format("--tile: '{}' is not XMIN,YMIN,XMAX,YMAX (metres)", text));
    at += used + 1;
  }
  if (!(t[2] > t[0] && t[3] > t[1]))
    throw std::invalid_argument(fmt::format("--tile: '{}' has XMAX <= XMIN or YMAX <= YMIN", text));
  return t;
}

std::array<double, 4> lattice_tile(const RowLayout& l) {
  const double ps = l.plant_spacing, rs = l.row_spacing;
  // A spacing of 1e-300 is above 0, but the tile's area is not (it was refused as '--tile: ... has
  // no area', for a tile no one gave).
  if (!(ps > 0) || !(rs > 0) || !(ps * rs > 0))
    throw std::invalid_argument(fmt::format(
        "the layout's lattice has no area (plant spacing {:g} m x row spacing {:g} m): give --tile "
        "XMIN,YMIN,XMAX,YMAX or --no-periodic",
        ps, rs));
  if (l.double_rows) {
    if (l.rows % 2 != 0)
      throw std::invalid_argument(
          fmt::format("double rows repeat by pairs, and the stand has {} rows: give an even --rows, --tile "
                      "or --no-periodic",
                      l.rows));
    const double mid = *l.double_rows / 2;
    return {-ps / 2, mid - rs / 2, (l.per_row - 0.5) * ps, mid + (l.rows / 2 - 0.5) * rs};
  }
  return {-ps / 2, -rs / 2, (l.per_row - 0.5) * ps, (l.rows - 0.5) * rs};
}

namespace {

/// The row layout a stand's report.json gives (none for a positions file); `path` names it.
template <typename Json>
std::optional<RowLayout> report_layout(const Json& j, const std::string& path) {
  try {
    const auto& l = j.at("config").at("layout");
    if (l.contains("positions")) return std::nullopt;
    // Checked as canopy stand's options are: the light's tile and LAI follow from them (a rows of
    // 2.5 read as 2, one of 1e30 overflowed).
    const auto whole = [&](const char* key) {
      const auto& v = l.at(key);
      if (!v.is_number_integer() || v.template get<long long>() < 1 ||
          v.template get<long long>() > INT32_MAX)
        throw std::invalid_argument(
            fmt::format("{}: config.layout.{} must be a whole number from 1 to {}, got {}", path, key,
                        INT32_MAX, v.dump()));
      return static_cast<int>(v.template get<long long>());
    };
    const auto metres = [&](const char* key) {
      const auto& v = l.at(key);
      if (!v.is_number() ||
          !(v.template get<double>() >= 0 && v.template get<double>() <= kMaxPlantCoordinate))
        throw std::invalid_argument(
            fmt::format("{}: config.layout.{} must be a number of metres from 0 to {:g}, got {}", path, key,
                        kMaxPlantCoordinate, v.dump()));
      return v.template get<double>();
    };
    RowLayout r;
    r.rows = whole("rows");
    r.per_row = whole("per_row");
    r.row_spacing = metres("row_spacing");
    r.plant_spacing = metres("plant_spacing");
    if (!l.at("double_rows").is_null()) r.double_rows = metres("double_rows");
    r.jitter = metres("jitter");  // how far plants may stand from the layout's places
    return r;
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(fmt::format("{}: no layout in its config ({})", path, e.what()));
  }
}

}  // namespace

std::optional<RowLayout> folder_layout(const std::string& dir) {
  const std::string path = dir + "/report.json";
  // Without a report (Stand.export writes none) the layout is not known: a tile must be given.
  std::error_code ec;
  if (!std::filesystem::exists(std::filesystem::symlink_status(path, ec))) return std::nullopt;
  std::string text;
  try {
    text = read_input_file(path, "report", kMaxReportBytes);  // a regular file of bounded size
  } catch (const std::exception& e) {
    throw std::invalid_argument(fmt::format("{} (a folder written by canopy stand holds it)", e.what()));
  }
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(fmt::format("{}: no layout in its config ({})", path, e.what()));
  }
  return report_layout(j, path);
}

#ifdef CANOPY_HAVE_LIGHT
light::LightConfig light_config(const LightOptions& o, const Stand& s, const std::optional<RowLayout>& layout,
                                LightSetup& setup) {
  light::LightConfig c;
  setup.suns = parse_suns(o);
  for (const SunSpec& x : setup.suns) c.suns.push_back({x.elevation_deg, x.azimuth_deg});
  c.sky = light::parse_sky(o.sky);
  c.sky_directions = o.sky_directions;
  c.periodic = !o.no_periodic;
  c.error = o.error;
  c.plant_error = o.plant_error;
  c.rays_per_m2 = o.rays_per_m2;
  c.layer_m = o.layer;
  c.seed = o.ray_seed;
  c.caster = light::parse_caster(o.caster);
  std::array<double, 4> t{};
  if (!o.tile.empty()) {
    t = parse_tile(o.tile);
  } else if (layout) {
    t = lattice_tile(*layout);
  } else if (o.no_periodic) {
    // An isolated stand from a positions file: its plants' footprint (plant origins, widened by
    // the mean distance to a neighbour's share, i.e. half the side of each plant's square).
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    for (const PlantRecord& p : s.plants)
      x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
    const double pad = s.plant_count() > 1
                           ? 0.5 * std::sqrt((x1 - x0) * (y1 - y0) / static_cast<double>(s.plant_count()))
                           : 0.5;
    t = {x0 - std::max(pad, 0.05), y0 - std::max(pad, 0.05), x1 + std::max(pad, 0.05),
         y1 + std::max(pad, 0.05)};
  } else {
    throw std::invalid_argument(
        "a stand from a positions file (or a folder without report.json, as Stand.export writes it) has no "
        "lattice: give its tile with --tile XMIN,YMIN,XMAX,YMAX (or --no-periodic)");
  }
  // An isolated stand's tile is the ground it stands on, whose light the fractions are over: a
  // tile that leaves plants out makes them the light of ground the stand does not stand on, and
  // a small one asks for rays by the billion (its errors are asked over its light).
  if (o.no_periodic && !o.tile.empty())
    for (std::size_t p = 0; p < s.plant_count(); ++p) {
      const PlantRecord& pl = s.plants[p];
      if (!(pl.x >= t[0] && pl.x <= t[2] && pl.y >= t[1] && pl.y <= t[3]))
        throw std::invalid_argument(
            fmt::format("--tile {}: with --no-periodic the tile is the ground the stand stands on (the "
                        "fractions are over "
                        "its light) and must hold every plant's base; plant {} stands at ({:.4g}, {:.4g})",
                        o.tile, p, pl.x, pl.y));
    }
  const Vec3d org = s.stand_origin;
  c.tile = {t[0] - org.x, t[1] - org.y, t[2] - org.x, t[3] - org.y};
  setup.tile = t;
  light::check_config(c);
  return c;
}
#endif

LightOutcome run_light(LightOptions o, bool print) {
#ifndef CANOPY_HAVE_LIGHT
  (void)o, (void)print;
  throw std::invalid_argument(
      "canopy light: this build has no ray caster (Embree was not found: apt-get install libembree-dev, then "
      "build again)");
#else
  const ThreadLimit thread_limit(o.threads);
  {
    // Bad options fail before any work (from a grammar: before the stand is grown and written).
    light::LightConfig v;
    for (const SunSpec& x : parse_suns(o)) v.suns.push_back({x.elevation_deg, x.azimuth_deg});
    v.sky = light::parse_sky(o.sky), v.sky_directions = o.sky_directions, v.error = o.error,
    v.plant_error = o.plant_error;
    v.rays_per_m2 = o.rays_per_m2, v.layer_m = o.layer, v.tile = {0, 0, 1, 1};
    v.caster = light::parse_caster(o.caster);
    if (!o.tile.empty()) (void)parse_tile(o.tile);
    light::check_config(v);
    if (!std::filesystem::is_directory(o.source) && o.tile.empty() && !o.no_periodic) {
      StandOptions probe = o.stand;
      probe.grammar = o.source;
      RowLayout l = plan_stand(probe).layout;
      // The command line's positions file, or the one the grammar's stand entry names.
      if (!probe.positions.empty())
        throw std::invalid_argument(
            "a stand from a positions file has no lattice: give its tile with --tile XMIN,YMIN,XMAX,YMAX (or "
            "--no-periodic)");
      if (o.stand.target.set()) l.plant_spacing = 1;  // chosen later: any spacing above 0
      (void)lattice_tile(l);
    }
  }
  // Where rasterized passes are drawn (a GPU as --backend chooses one): refused before any work.
  std::string device_note;
  // (--caster trace draws nothing: no GPU is started for it.)
  const std::unique_ptr<light::RasterDevice> device =
      o.caster == "trace" ? nullptr : make_light_device(o.stand.detect.backend, device_note);
  LightOutcome out;
  LightSetup setup;
  std::optional<light::LightResult> result;
  std::size_t plants = 0;
  std::vector<std::string> light_notes;  // about the light made, said once it is
  // The light of `stand` (laid out as `layout`) into `files`.
  const auto light_files = [&](const Stand& stand, std::optional<RowLayout> layout, OutputSet& files) {
    if (!o.tile.empty()) layout.reset();
    light::LightConfig cfg = light_config(o, stand, layout, setup);
    cfg.device = device.get();
    PrototypeLibrary lib;
    result = light::compute_light(stand, lib, cfg);
    if (!result->periodic) {
      double most = result->ground.fraction.value;
      for (const light::DirectionLight& d : result->direct) most = std::max(most, d.fraction.value);
      if (result->diffuse) most = std::max(most, result->diffuse->fraction.value);
      if (most > 1)
        light_notes.push_back(fmt::format(
            "the isolated stand intercepts light from beyond its tile (a fraction of {:.3f}): its fractions "
            "are "
            "of the light on the tile, and exceed 1 where the stand's shadow is larger than the tile",
            most));
    }
    out.json = light_json(*result, stand, o, setup);
    out.csv = light_csv(*result, stand);
    plants = stand.plant_count();
    files.open("light.json").write(json_text(out.json, 2) + "\n");
    files.open("light.csv").write(out.csv);
  };
  if (std::filesystem::is_directory(o.source)) {
    // The folder and its stand as read: taken before and after reading (read_stand reads one set,
    // which a run replacing the folder meanwhile may have made the next one).
    FolderIdentity read = folder_identity(o.source, "organs.csv");
    Stand stand = read_stand(o.source);
    for (int again = 0; again < 3 && !(folder_identity(o.source, "organs.csv") == read); ++again) {
      read = folder_identity(o.source, "organs.csv");
      stand = read_stand(o.source);
    }
    // Said at once on the command line; Python warns with the outcome's notes.
    for (std::string& note : folder_count_notes(o.source, stand, read)) out.notes.push_back(std::move(note));
    if (print) print_notes(out.notes);
    out.dir = o.source;
    // Its names are the light's files: a folder under one is refused before any work.
    OutputSet files(out.dir, {"light.json", "light.csv"});
    files.require_folder(read, "organs.csv");  // a stand written there meanwhile does not take this light
    std::optional<RowLayout> layout = folder_layout(o.source);
    // The lattice tile holds rows x per_row plants: a report of another stand would light this one
    // over another tile (a 5 x 10 stand read with 2 rows: LAI 3.3 instead of 1.3).
    if (layout && o.tile.empty() &&
        static_cast<std::uint64_t>(layout->rows) * static_cast<std::uint64_t>(layout->per_row) !=
            stand.plant_count())
      throw std::invalid_argument(fmt::format(
          "{}/report.json: its layout ({} rows of {} plants) does not match the {} plants of plants.csv: the "
          "files are not of one stand; give the tile with --tile XMIN,YMIN,XMAX,YMAX",
          o.source, layout->rows, layout->per_row, stand.plant_count()));
    // The same count in another shape (3 rows of 1 for 1 row of 3) lit the stand over another
    // tile: each plant must stand within the layout's jitter of its place in the layout.
    if (layout && o.tile.empty()) {
      RowLayout nominal = *layout;
      nominal.jitter = 0;
      const std::vector<PlantPlacement> at = row_layout(nominal);
      const double slack = layout->jitter + 1e-6;
      for (std::size_t p = 0; p < at.size(); ++p) {
        const PlantRecord& r = stand.plants[p];
        if (std::hypot(at[p].x - r.x, at[p].y - r.y) > slack)
          throw std::invalid_argument(fmt::format(
              "{}/report.json: its layout ({} rows of {} plants) places plant {} at ({:g}, {:g}) (within "
              "{:g} m), "
              "plants.csv at ({:g}, {:g}): the files are not of one stand; give the tile with --tile "
              "XMIN,YMIN,XMAX,YMAX",
              o.source, layout->rows, layout->per_row, p, at[p].x, at[p].y, layout->jitter, r.x, r.y));
      }
    }
    light_files(stand, layout, files);
    files.commit_all();
  } else {
    o.stand.grammar = o.source;
    o.stand.detect.threads = o.threads;
    out.dir = o.stand.out;
    // The light is made with the stand's files and put in place with them: a refusal that needs
    // the grown stand (a tile under which it repeats too often, rays past the limit) leaves the
    // folder as it was. The layout is the one run (a target chooses its plant spacing).
    o.stand.more_files = [&](const Stand& stand, const nlohmann::ordered_json& report, OutputSet& files) {
      light_files(stand, report_layout(report, out.dir + "/report.json"), files);
    };
    out.notes = run_stand(o.stand, print).notes;
  }
  if (print) print_notes(light_notes);
  out.notes.insert(out.notes.end(), light_notes.begin(), light_notes.end());
  const light::LightResult& r = *result;
  if (print) {
    const auto pm = [](const light::Estimate& e) {
      return std::isnan(e.value) ? std::string("none (no leaflets)")
                                 : fmt::format("{:.4f} +- {:.4f}", e.value, e.se);
    };
    fmt::print(
        "light: {} plants, tile {:.3g} x {:.3g} m ({}), LAI {:.3f}, {} rays in {:.2f} s (scene {:.2f} s)\n",
        plants, r.tile.width(), r.tile.height(), r.periodic ? "periodic" : "isolated", r.lai, r.rays,
        r.trace_s, r.scene_s);
    if (r.raster_passes)
      fmt::print("  {} of them answered by drawing the stand in {} passes ({:.2f} s, on {})\n", r.raster_rays,
                 r.raster_passes, r.raster_s, device ? device_note : std::string("the host's threads"));
    fmt::print("  {:<34} {}  ({} rays)\n", "ground cover", pm(r.ground.fraction), r.ground.rays);
    for (std::size_t i = 0; i < r.direct.size(); ++i)
      fmt::print("  {:<34} {}  ({} rays)\n",
                 fmt::format("sun at {:.1f} deg, azimuth {:.1f}{}", r.direct[i].elevation_deg,
                             r.direct[i].azimuth_deg,
                             setup.suns[i].from_hours ? fmt::format(" ({} h)", setup.suns[i].hour) : std::string()),
                 pm(r.direct[i].fraction), r.direct[i].rays);
    if (r.diffuse) {
      fmt::print(
          "  {:<34} {}  ({} rays)\n",
          fmt::format("diffuse ({} sky, {} directions)", light::sky_name(r.sky), r.sky_directions.size()),
          pm(r.diffuse->fraction), r.diffuse->rays);
      fmt::print("  {:<34} {}\n", "STAR (leaflets, over the sky)", pm(r.diffuse->star));
    }
    if (std::isnan(r.leaf_angles.mean_inclination_deg))
      fmt::print("  {:<34} none (no leaflets)\n", "mean leaflet inclination");
    else fmt::print("  {:<34} {:.1f} deg\n", "mean leaflet inclination", r.leaf_angles.mean_inclination_deg);
    if (r.organs_skipped)
      fmt::print("  note: {} organs flattened to nothing were left out\n", r.organs_skipped);
    fmt::print("wrote {}/light.json and {}/light.csv\n", out.dir, out.dir);
  }
  return out;
#endif
}

}  // namespace canopy::cli
