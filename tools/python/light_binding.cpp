// canopy.Stand.light and canopy.light: canopy light on a stand held by Python or on a folder or
// grammar, returning light.json as a dict (with light.csv's columns as NumPy arrays for a Stand).
#include "geometry/split_list.hpp"
#include "geometry/thread_limit.hpp"
#include "tools/light_device.hpp"
#include "tools/light_run.hpp"
#include "tools/python/common.hpp"

#include <pybind11/stl.h>

#include <sstream>

namespace canopy::python {
namespace {

/// Keyword options shared by Stand.light and canopy.light; false when `k` is not one of them.
bool light_option(cli::LightOptions& o, const std::string& k, py::handle v) {
  if (k == "suns") {
    o.suns.clear();
    for (auto s : v) {
      const auto pair = s.cast<std::pair<double, double>>();
      o.suns.push_back(fmt::format("{},{}", pair.first, pair.second));
    }
  } else if (k == "latitude") o.latitude = v.cast<double>();
  else if (k == "day") o.day = v.cast<int>();
  else if (k == "hours") {
    if (py::isinstance<py::str>(v)) o.hours = v.cast<std::string>();
    else
      for (auto x : v) o.hours += (o.hours.empty() ? "" : ",") + fmt::format("{}", x.cast<double>());
  } else if (k == "sky") o.sky = v.cast<std::string>();
  else if (k == "sky_directions") o.sky_directions = v.cast<int>();
  else if (k == "tile") {
    const auto t = v.cast<std::array<double, 4>>();
    o.tile = fmt::format("{},{},{},{}", t[0], t[1], t[2], t[3]);
  } else if (k == "periodic") o.no_periodic = !v.cast<bool>();
  else if (k == "error") o.error = v.cast<double>();
  else if (k == "plant_error") o.plant_error = v.cast<double>();
  else if (k == "rays_per_m2") o.rays_per_m2 = v.cast<double>();
  else if (k == "layer") o.layer = v.cast<double>();
  else if (k == "ray_seed") o.ray_seed = v.cast<std::uint64_t>();
  else if (k == "threads") o.threads = v.cast<int>();
  else if (k == "caster") o.caster = v.cast<std::string>();
  else if (k == "backend") o.stand.detect.backend = v.cast<std::string>();
  else return false;
  return true;
}

#ifdef CANOPY_HAVE_LIGHT
/// light.csv's columns as NumPy arrays (float64), keyed by name.
py::dict csv_columns(const std::string& csv) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> names = split_list(line);
  std::vector<std::vector<double>> cols(names.size());
  while (std::getline(in, line)) {
    const std::vector<std::string> cells = split_list(line);
    for (std::size_t c = 0; c < names.size(); ++c) cols[c].push_back(std::stod(cells.at(c)));
  }
  py::dict out;
  for (std::size_t c = 0; c < names.size(); ++c)
    out[py::str(names[c])] = py::array_t<double>(static_cast<py::ssize_t>(cols[c].size()), cols[c].data());
  return out;
}
#endif

}  // namespace

void bind_light(py::module_& m) {
  auto cls = py::reinterpret_borrow<py::class_<PyStand, std::shared_ptr<PyStand>>>(m.attr("Stand"));
  cls.def(
      "light",
      [](PyStand& s, py::kwargs kwargs) {
#ifndef CANOPY_HAVE_LIGHT
        (void)s, (void)kwargs;
        throw std::invalid_argument("light: this build has no ray caster (Embree was not found)");
#else
        cli::LightOptions o;
        o.source = s.grammar;
        for (auto item : kwargs) {
          const std::string k = py::str(item.first);
          if (!light_option(o, k, item.second))
            throw std::invalid_argument(fmt::format("light: unknown option '{}'", k));
        }
        nlohmann::ordered_json j;
        std::string csv;
        {
          py::gil_scoped_release nogil;
          const ThreadLimit thread_limit(o.threads);
          cli::LightSetup setup;
          light::LightConfig cfg =
              cli::light_config(o, s.stand, o.tile.empty() ? s.layout : std::nullopt, setup);
          std::string note;
          const std::unique_ptr<light::RasterDevice> device =
              o.caster == "trace" ? nullptr : cli::make_light_device(o.stand.detect.backend, note);
          cfg.device = device.get();
          PrototypeLibrary lib;
          const light::LightResult r = light::compute_light(s.stand, lib, cfg);
          j = cli::light_json(r, s.stand, o, setup);
          csv = cli::light_csv(r, s.stand);
        }
        py::dict out = json_to_py(j);
        out["per_plant"] = csv_columns(csv);
        return out;
#endif
      },
      "Light interception (canopy light): suns=[(elevation, azimuth), ...], latitude=, day=, hours=[...], "
      "sky='soc', "
      "sky_directions=46, tile=(xmin, ymin, xmax, ymax), periodic=True, error=0.002, plant_error=, "
      "rays_per_m2=, layer=0.1, "
      "ray_seed=1, caster='auto', backend='auto', threads=0. Returns light.json as a dict, with 'per_plant': "
      "light.csv's columns as arrays. "
      "The tile "
      "defaults to the lattice of the rows the stand was grown in (or read from).");

  m.def(
      "light",
      [](py::object source, py::dict kwargs) {
        cli::LightOptions o;
        o.source = path_of(source);
        for (auto item : kwargs) {
          const std::string k = py::str(item.first);
          py::handle v = item.second;
          if (light_option(o, k, v)) continue;
          // From a grammar: canopy stand's options.
          cli::StandOptions& st = o.stand;
          if (k == "out") st.out = path_of(v);
          else if (k == "steps") st.steps = v.cast<int>();
          else if (k == "set") st.set = overrides(v.cast<std::map<std::string, double>>());
          else if (k == "lod") st.lod = v.cast<int>();
          else if (k == "rows") st.rows.rows = v.cast<int>();
          else if (k == "per_row") st.rows.per_row = v.cast<int>();
          else if (k == "row_spacing") st.rows.row_spacing = v.cast<double>();
          else if (k == "plant_spacing") st.rows.plant_spacing = v.cast<double>();
          else if (k == "double_rows") st.rows.double_rows = v.cast<double>();
          else if (k == "jitter") st.rows.jitter = v.cast<double>();
          else if (k == "random_rotation") st.random_rotation = v.cast<bool>();
          else if (k == "seed") st.rows.seed = v.cast<std::uint64_t>();
          else if (k == "positions") st.positions = path_of(v);
          else if (k == "backend") st.detect.backend = v.cast<std::string>();
          else if (k == "no_resolve") st.resolve.no_resolve = v.cast<bool>();
          else if (k == "target_lai") st.target.lai = v.cast<double>();
          else if (k == "target_ground_cover") st.target.ground_cover = v.cast<double>();
          else throw std::invalid_argument(fmt::format("light: unknown option '{}'", k));
        }
        cli::LightOutcome r;
        {
          py::gil_scoped_release nogil;
          r = cli::run_light(o, false);
        }
        return json_to_py(r.json);
      },
      py::arg("source"), py::arg("options") = py::dict(),
      "canopy light SOURCE (a stand folder, or a grammar with canopy stand's options and out=DIR): writes "
      "light.json and "
      "light.csv and returns light.json as a dict.");
}

}  // namespace canopy::python
