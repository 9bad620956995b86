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
#include "tools/python/keywords.hpp"
#include "tools/stand_options.hpp"
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

namespace {

/// `canopy COMMAND GRAMMAR -o OUT` with keyword options: the options `add` registers (the
/// command's own), parsed from the keywords.
template <typename Register>
auto parse_command(Register add, const std::string& command, py::handle grammar, py::handle out,
                   const py::dict& kwargs) {
  CLI::App app;
  auto options = add(app);
  py::dict with_out = kwargs.attr("copy")();
  with_out["out"] = out;
  parse_keywords(app, command, {path_of(grammar)}, with_out);
  return options;
}

}  // namespace

PYBIND11_MODULE(_canopy, m) {
  m.doc() = "canopy: penetration-free plant stands from parametric L-system grammars (C++ core)";
  m.attr("__version__") = CANOPY_VERSION;
  // pybind11 sets up NumPy's C API once, on the first call that makes an array, under a lock of
  // its own while it imports NumPy; an import can let go of the GIL, and a second thread then
  // waiting on that lock with the GIL held stalls both for good (two threads' first
  // Stand.detect). Set up here, at import, where nothing else runs.
  py::module_::import("numpy");
  (void)py::dtype::of<double>();

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
      [](py::object grammar_arg, py::object steps_arg, py::object seed_arg,
         const std::map<std::string, double>& set, bool stats, bool interpreted,
         py::object max_modules_arg) -> py::object {
        const std::string grammar = path_of(grammar_arg);
        // The counts checked as canopy derive checks them (a ValueError with its message, not
        // pybind11's TypeError for an int that does not fit).
        const std::optional<int> steps = whole_arg<int>(steps_arg, "steps", cli::whole_in(0, kMaxSteps));
        const std::optional<std::uint64_t> seed = whole_arg<std::uint64_t>(seed_arg, "seed", cli::kSeed);
        const std::size_t max_modules =
            whole_arg<std::size_t>(max_modules_arg, "max_modules", cli::whole_in(1, INT64_MAX)).value();
        LoadOptions lo;
        for (const auto& s : overrides(set)) lo.overrides.push_back(parse_override(s));
        std::string text;
        std::vector<std::string> notes;
        {
          py::gil_scoped_release nogil;
          const Grammar g = load_grammar(grammar, lo);
          notes = g.notes;
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
        warn_notes(notes);
        if (stats) return py::module_::import("json").attr("loads")(text);
        return py::str(text);
      },
      py::arg("grammar"), py::kw_only(), py::arg("steps") = py::none(), py::arg("seed") = py::none(),
      py::arg("set") = std::map<std::string, double>{}, py::arg("stats") = false,
      py::arg("interpreted") = false, py::arg("max_modules") = py::int_(kDefaultMaxModules),
      "The derived string (canopy derive), or with stats=True its module counts as a dict.");

  bind_stand(m);
  bind_light(m);

  m.def(
      "stand",
      [](py::object grammar, py::object out, py::dict kwargs, py::object progress) {
        const auto o = parse_command(cli::register_stand, "stand", grammar, out, kwargs);
        Callback cb(std::move(progress));
        cli::StandOutcome r;
        try {
          py::gil_scoped_release nogil;
          std::function<void(const ResolveProgress&)> hook;
          if (cb.set()) hook = [&](const ResolveProgress& p) { cb(p.round, p.contacts, p.seconds); };
          r = cli::run_stand(*o, false, hook);
        } catch (const CallbackRaised&) {
          cb.rethrow();
        }
        warn_notes(r.notes);
        return json_to_py(r.report);
      },
      py::arg("grammar"), py::arg("out"), py::arg("options") = py::dict(), py::arg("progress") = py::none(),
      "canopy stand GRAMMAR -o OUT with the command line's options (underscores for dashes), read by its "
      "parser; returns report.json.");

  m.def(
      "sweep",
      [](py::object grammar, py::object out, py::dict kwargs, py::object progress) {
        const auto o = parse_command(cli::register_sweep, "sweep", grammar, out, kwargs);
        Callback cb(std::move(progress));
        cli::SweepOutcome r;
        try {
          py::gil_scoped_release nogil;
          cli::SweepCallback hook;
          if (cb.set())
            hook = [&](std::size_t i, std::size_t total, const cli::RunRow& row) {
              cb(i, total, std::map<std::string, std::string>(row.begin(), row.end()));
            };
          r = cli::run_sweep(*o, false, hook);
        } catch (const CallbackRaised&) {
          cb.rethrow();
        }
        warn_notes(r.notes);
        py::dict d;
        d["total"] = r.total, d["ran"] = r.ran, d["failed"] = r.failed,
        d["failed_in_table"] = r.failed_in_table;
        return d;
      },
      py::arg("grammar"), py::arg("out"), py::arg("options") = py::dict(), py::arg("progress") = py::none(),
      "canopy sweep GRAMMAR -o OUT with the command line's options, read by its parser (lists as Python "
      "lists "
      "or 'a,b' / 'start:stop:step'); progress(index, total, row) after each run. Returns counts (total, "
      "ran, "
      "failed now, failed_in_table: runs.csv's failed rows of the grid, earlier ones too); the rows are in "
      "OUT/runs.csv "
      "and OUT/summary.csv.");
}
