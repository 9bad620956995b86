// canopy.Stand.light and canopy.light: canopy light on a stand held by Python or on a folder or
// grammar, returning light.json as a dict (with light.csv's columns as NumPy arrays for a Stand).
#include "geometry/split_list.hpp"
#include "geometry/thread_limit.hpp"
#include "tools/light_device.hpp"
#include "tools/light_run.hpp"
#include "tools/python/common.hpp"
#include "tools/python/keywords.hpp"
#include "tools/stand_options.hpp"

#include <pybind11/stl.h>

#include <limits>

#include <sstream>

namespace canopy::python {
namespace {

/// Python's names for options the command line spells otherwise.
const std::map<std::string, std::string> kLightNames{{"suns", "sun"}};

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
    // An empty cell (the STAR of a plant without leaflets) is undefined: NaN.
    for (std::size_t c = 0; c < names.size(); ++c)
      cols[c].push_back(cells.at(c).empty() ? std::numeric_limits<double>::quiet_NaN()
                                            : std::stod(cells.at(c)));
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
        const StandInUse in_use(s, "Stand.light");
#ifndef CANOPY_HAVE_LIGHT
        (void)s, (void)kwargs;
        throw std::invalid_argument("light: this build has no ray caster (Embree was not found)");
#else
        CLI::App app;
        const std::shared_ptr<cli::LightOptions> options = cli::register_light(app);
        parse_keywords(app, "Stand.light", {"stand"}, kwargs, kLightNames);
        cli::refuse_given(
            app,
            {cli::kGrowGroup, cli::kLayoutGroup, cli::kFilesGroup, cli::kResolveGroup, cli::kDetectGroup},
            {"--threads", "--backend"},
            "Stand.light lights the stand it is called on (canopy.light grows one from a grammar)");
        cli::LightOptions& o = *options;
        o.threads = o.stand.detect.threads;
        o.source = s.grammar;
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
        CLI::App app;
        const std::shared_ptr<cli::LightOptions> o = cli::register_light(app);
        parse_keywords(app, "light", {path_of(source)}, kwargs, kLightNames);
        cli::check_light_command(app, *o);
        cli::LightOutcome r;
        {
          py::gil_scoped_release nogil;
          r = cli::run_light(*o, false);
        }
        warn_notes(r.notes);
        return json_to_py(r.json);
      },
      py::arg("source"), py::arg("options") = py::dict(),
      "canopy light SOURCE (a stand folder, or a grammar with canopy stand's options and out=DIR): writes "
      "light.json and "
      "light.csv and returns light.json as a dict.");
}

}  // namespace canopy::python
