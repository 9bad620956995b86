// The canopy Python module (pybind11): the command line's operations on the same library code,
// organ arrays as NumPy views of the stand's memory, errors as Python exceptions carrying the
// command line's located messages. Long calls release the GIL; progress callbacks take it back.
#include "resolution/resolve.hpp"
#include "geometry/export.hpp"
#include "geometry/layout.hpp"
#include "geometry/organ_mesh.hpp"
#include "lsystem/derive.hpp"
#include "lsystem/error.hpp"
#include "lsystem/grow.hpp"
#include "lsystem/module_format.hpp"
#include "tools/detect_options.hpp"
#include "tools/resolve_options.hpp"
#include "tools/python/common.hpp"
#include "tools/stand_run.hpp"
#include "tools/sweep_run.hpp"

#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdio>
#include <cstring>
#include <optional>

namespace py = pybind11;
using namespace canopy;

using namespace canopy::python;

PYBIND11_MODULE(_canopy, m) {
  m.doc() = "canopy: penetration-free plant stands from parametric L-system grammars (C++ core)";
  m.attr("__version__") = CANOPY_VERSION;

  static py::exception<ModuleCapError> module_cap(m, "ModuleCapError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const GrammarFileError& e) {
      PyErr_SetString(PyExc_FileNotFoundError, e.what());
    } catch (const FileNotFound& e) {
      PyErr_SetString(PyExc_FileNotFoundError, e.what());
    } catch (const GrammarError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const ModuleCapError& e) {
      module_cap(e.what());
    } catch (const std::invalid_argument& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });

  m.def(
      "derive",
      [](py::object grammar_arg, std::optional<int> steps, std::optional<std::uint64_t> seed,
         const std::map<std::string, double>& set, bool stats, bool interpreted,
         std::size_t max_modules) -> py::object {
        const std::string grammar = path_of(grammar_arg);
        LoadOptions lo;
        for (const auto& s : overrides(set)) lo.overrides.push_back(parse_override(s));
        std::string text;
        {
          py::gil_scoped_release nogil;
          const Grammar g = load_grammar(grammar, lo);
          DeriveRequest req;
          req.steps = steps;
          req.seed = seed;
          req.max_modules = max_modules;
          ModuleString s = derive(g, req);
          if (interpreted) s = interpret(g, s, seed.value_or(g.seed), max_modules);
          if (stats) {
            text = stats_json(g, s);
          } else {
            text = format_modules(g, s);
          }
        }
        if (stats) return py::module_::import("json").attr("loads")(text);
        return py::str(text);
      },
      py::arg("grammar"), py::kw_only(), py::arg("steps") = py::none(), py::arg("seed") = py::none(),
      py::arg("set") = std::map<std::string, double>{}, py::arg("stats") = false,
      py::arg("interpreted") = false, py::arg("max_modules") = kDefaultMaxModules,
      "The derived string (canopy derive), or with stats=True its module counts as a dict.");

  bind_stand(m);
  bind_light(m);

  m.def(
      "stand",
      [](const std::string& grammar, const std::string& out, py::dict kwargs, py::object progress) {
        cli::StandOptions o;
        o.grammar = grammar;
        o.out = out;
        for (auto item : kwargs) {
          const std::string k = py::str(item.first);
          py::handle v = item.second;
          if (k == "steps") o.steps = v.cast<int>();
          else if (k == "set") o.set = overrides(v.cast<std::map<std::string, double>>());
          else if (k == "lod") o.lod = v.cast<int>();
          else if (k == "formats") o.formats = v.cast<std::string>();
          else if (k == "glb_instancing") o.glb_instancing = v.cast<bool>();
          else if (k == "glb_compact") o.glb_compact = v.cast<bool>();
          else if (k == "max_modules") o.max_modules = v.cast<std::size_t>();
          else if (k == "rows") o.rows.rows = v.cast<int>();
          else if (k == "per_row") o.rows.per_row = v.cast<int>();
          else if (k == "row_spacing") o.rows.row_spacing = v.cast<double>();
          else if (k == "plant_spacing") o.rows.plant_spacing = v.cast<double>();
          else if (k == "double_rows") o.rows.double_rows = v.cast<double>();
          else if (k == "jitter") o.rows.jitter = v.cast<double>();
          else if (k == "random_rotation")
            o.rows.random_rotation = v.cast<bool>();  // False too: over the grammar's entry
          else if (k == "seed") o.rows.seed = v.cast<std::uint64_t>();
          else if (k == "positions") o.positions = path_of(v);
          else if (k == "any_grammar_path") o.any_grammar_path = v.cast<bool>();
          else if (k == "level") o.detect.level = v.cast<std::string>();
          else if (k == "clearance") o.detect.clearance = v.cast<double>();
          else if (k == "collide") o.detect.collide = v.cast<std::string>();
          else if (k == "backend") o.detect.backend = v.cast<std::string>();
          else if (k == "threads") o.detect.threads = v.cast<int>();
          else if (k == "no_resolve") o.resolve.no_resolve = v.cast<bool>();
          else if (k == "max_rounds") o.resolve.max_rounds = v.cast<int>();
          else if (k == "resolve_clearance") o.resolve.clearance = v.cast<double>();
          else if (k == "resolve_level") o.resolve.level = v.cast<std::string>();
          else if (k == "target_lai") o.target.lai = v.cast<double>();
          else if (k == "target_ground_cover") o.target.ground_cover = v.cast<double>();
          else if (k == "target_error") o.target.error = v.cast<double>();
          else throw std::invalid_argument(fmt::format("stand: unknown option '{}'", k));
        }
        if (!parse_contact_level(o.detect.level))
          throw std::invalid_argument(
              fmt::format("level: '{}' is not plant, leaf, organ or exact", o.detect.level));
        Callback cb(std::move(progress));
        cli::StandOutcome r;
        try {
          py::gil_scoped_release nogil;
          std::function<void(const ResolveProgress&)> hook;
          if (cb.set()) hook = [&](const ResolveProgress& p) { cb(p.round, p.contacts, p.seconds); };
          r = cli::run_stand(o, false, hook);
        } catch (const CallbackRaised&) {
          cb.rethrow();
        }
        return json_to_py(r.report);
      },
      py::arg("grammar"), py::arg("out"), py::arg("options") = py::dict(), py::arg("progress") = py::none(),
      "canopy stand GRAMMAR -o OUT with the command line's options (underscores for dashes); returns "
      "report.json.");

  m.def(
      "sweep",
      [](const std::string& grammar, const std::string& out, py::dict kwargs, py::object progress) {
        cli::SweepOptions o;
        o.grammar = grammar;
        o.out = out;
        const auto list = [](py::handle v) -> std::string {
          if (py::isinstance<py::str>(v)) return v.cast<std::string>();
          std::string s;
          for (auto x : v) s += (s.empty() ? "" : ",") + fmt::format("{}", x.cast<double>());
          return s;
        };
        for (auto item : kwargs) {
          const std::string k = py::str(item.first);
          py::handle v = item.second;
          if (k == "plant_spacing") o.plant_spacing = list(v);
          else if (k == "row_spacing") o.row_spacing = list(v);
          else if (k == "density") o.density = list(v);
          else if (k == "steps") o.steps = list(v);
          else if (k == "seeds") o.seeds = v.cast<int>();
          else if (k == "rows") o.rows = v.cast<int>();
          else if (k == "per_row") o.per_row = v.cast<int>();
          else if (k == "jitter") o.jitter = v.cast<double>();
          else if (k == "random_rotation") o.random_rotation = v.cast<bool>();
          else if (k == "lod") o.lod = v.cast<int>();
          else if (k == "set") o.set = overrides(v.cast<std::map<std::string, double>>());
          else if (k == "retry_failed") o.retry_failed = v.cast<bool>();
          else if (k == "max_modules") o.max_modules = v.cast<std::size_t>();
          else if (k == "backend") o.detect.backend = v.cast<std::string>();
          else if (k == "threads") o.detect.threads = v.cast<int>();
          else if (k == "collide") o.detect.collide = v.cast<std::string>();
          else if (k == "no_resolve") o.resolve.no_resolve = v.cast<bool>();
          else if (k == "max_rounds") o.resolve.max_rounds = v.cast<int>();
          else if (k == "sun") o.sun = list(v);
          else if (k == "sky") o.sky = v.cast<std::string>();
          else if (k == "sky_directions") o.sky_directions = v.cast<int>();
          else if (k == "light_error") o.light_error = v.cast<double>();
          else if (k == "no_light") o.no_light = v.cast<bool>();
          else throw std::invalid_argument(fmt::format("sweep: unknown option '{}'", k));
        }
        if (o.seeds < 1 || o.rows < 1 || o.per_row < 1)
          throw std::invalid_argument("sweep: seeds, rows and per_row must be at least 1");
        Callback cb(std::move(progress));
        cli::SweepOutcome r;
        try {
          py::gil_scoped_release nogil;
          cli::SweepCallback hook;
          if (cb.set())
            hook = [&](std::size_t i, std::size_t total, const cli::RunRow& row) {
              cb(i, total, std::map<std::string, std::string>(row.begin(), row.end()));
            };
          r = cli::run_sweep(o, false, hook);
        } catch (const CallbackRaised&) {
          cb.rethrow();
        }
        py::dict d;
        d["total"] = r.total, d["ran"] = r.ran, d["failed"] = r.failed;
        return d;
      },
      py::arg("grammar"), py::arg("out"), py::arg("options") = py::dict(), py::arg("progress") = py::none(),
      "canopy sweep GRAMMAR -o OUT (lists as Python lists or 'a,b' / 'start:stop:step'); progress(index, "
      "total, row) after "
      "each run. Returns counts; the rows are in OUT/runs.csv and OUT/summary.csv.");
}
