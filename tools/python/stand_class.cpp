// canopy.Stand: a stand owned by Python, NumPy views of its organs, detection, resolution, export.
#include "geometry/export.hpp"
#include "geometry/layout.hpp"
#include "geometry/organ_mesh.hpp"
#include "geometry/thread_limit.hpp"
#include "lsystem/grow.hpp"
#include "tools/cli_common.hpp"
#include "tools/folder_counts.hpp"
#include "tools/light_run.hpp"
#include "tools/python/common.hpp"
#include "tools/python/positions_array.hpp"
#include "tools/python/keywords.hpp"
#include "tools/resolve_options.hpp"
#include "tools/stand_run.hpp"

#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstring>

namespace canopy::python {

void bind_stand(py::module_& m) {
  py::class_<PyStand, std::shared_ptr<PyStand>>(m, "Stand",
                                                "A stand of plants: organ arrays view its memory.")
      .def_static(
          "grow",
          [](py::object grammar_arg, std::optional<int> rows, std::optional<int> per_row,
             std::optional<double> row_spacing, std::optional<double> plant_spacing,
             std::optional<double> double_rows, std::optional<double> jitter,
             std::optional<bool> random_rotation, py::object seed_arg, py::object positions_arg,
             std::optional<int> steps, const std::map<std::string, double>& set, int lod, int threads,
             std::size_t max_modules) {
            const std::string grammar = path_of(grammar_arg);
            const bool positions = !positions_arg.is_none();
            // A whole number from 0 to 2^64 - 1, as --seed (pybind's cast said only "incompatible
            // arguments").
            std::optional<std::uint64_t> seed;
            if (!seed_arg.is_none()) {
              // Any integer (NumPy's too), never a bool or a float.
              const std::optional<std::string> whole = integer_text(seed_arg);
              seed = whole ? parse_seed(*whole) : std::nullopt;
              if (!seed)
                throw std::invalid_argument(
                    fmt::format("seed: needs a whole number from 0 to 18446744073709551615, got {}",
                                py::repr(seed_arg).cast<std::string>()));
            }
            // The command line's plan: the grammar loaded, the layout chosen (row options over the
            // grammar's stand entry field by field, else the positions file that entry names).
            cli::StandOptions o;
            o.grammar = grammar, o.set = overrides(set), o.steps = steps, o.lod = lod;
            o.detect.threads = threads, o.max_modules = max_modules;
            o.rows.rows = rows, o.rows.per_row = per_row, o.rows.row_spacing = row_spacing,
            o.rows.plant_spacing = plant_spacing, o.rows.double_rows = double_rows, o.rows.jitter = jitter,
            o.rows.random_rotation = random_rotation, o.rows.seed = seed;
            if (positions && cli::any_row_option(o.rows))
              throw std::invalid_argument("positions cannot be combined with row options");
            // Whole numbers of plants, as --rows and --per-row say (a negative count wrapped to
            // 2^64 - 1 plants in the size check).
            for (const auto& [name, count] : {std::pair{"rows", rows}, std::pair{"per_row", per_row}})
              if (count && *count < 1)
                throw std::invalid_argument(
                    fmt::format("{}: needs a whole number from 1 to 2147483647, got {}", name, *count));
            std::vector<PlantPlacement> given;
            if (positions) given = placements_of(positions_arg);
            cli::StandPlan plan = cli::plan_stand(o);
            warn_notes(plan.grammar.notes);
            auto out = std::make_shared<PyStand>();
            if (positions) {
              plan.request.plants = std::move(given);
            } else if (o.positions.empty()) {
              // Said before placing and growing, with the command line's estimate, when the stand
              // cannot fit (10^10 plants' placements alone ran out of memory).
              cli::place_plan(plan, o);
              out->layout = plan.layout;
            }
            if (!out->layout) cli::check_plan_fits(plan, plan.request.plants.size());
            out->inputs = cli::plan_inputs(plan, o);
            GrowRequest& req = plan.request;
            out->grammar = grammar;
            {
              py::gil_scoped_release nogil;
              const ThreadLimit thread_limit(threads);
              out->stand = grow_stand(req);
            }
            return out;
          },
          py::arg("grammar"), py::kw_only(), py::arg("rows") = py::none(), py::arg("per_row") = py::none(),
          py::arg("row_spacing") = py::none(), py::arg("plant_spacing") = py::none(),
          py::arg("double_rows") = py::none(), py::arg("jitter") = py::none(),
          py::arg("random_rotation") = py::none(), py::arg("seed") = py::none(),
          py::arg("positions") = py::none(), py::arg("steps") = py::none(),
          py::arg("set") = std::map<std::string, double>{}, py::arg("lod") = kDefaultLod,
          py::arg("threads") = 0, py::arg("max_modules") = kDefaultMaxModules,
          "Grows a stand: rows (as canopy stand's layout options, each given overriding that field of the "
          "grammar's stand "
          "entry) or an N x 4 array "
          "of positions x, y, rotation (degrees), seed.")
      .def_static(
          "read",
          [](py::object dir_arg) {
            const std::string dir = path_of(dir_arg);
            auto out = std::make_shared<PyStand>();
            FolderIdentity before;
            {
              py::gil_scoped_release nogil;
              before = folder_identity(dir, "organs.csv");
              out->stand = read_stand(dir);
              out->layout = cli::folder_layout(dir);
            }
            warn_notes(cli::folder_count_notes(dir, out->stand, before));
            return out;
          },
          py::arg("dir"), "Reads a stand back from a folder written by canopy stand.")
      .def_property_readonly("plant_count", [](const PyStand& s) { return s.stand.plant_count(); })
      .def_property_readonly(
          "ids",
          [](const PyStand& s) {
            py::array_t<std::int64_t> a(static_cast<py::ssize_t>(s.stand.organ_count()));
            auto* p = a.mutable_data();
            for (std::size_t i = 0; i < s.stand.organ_count(); ++i) p[i] = static_cast<std::int64_t>(i);
            return read_only(a);  // as the views: canopy's arrays change only through its calls
          },
          "Organ ids (global, as in organs.csv and contacts): 0 .. organ_count - 1.")
      .def_property_readonly("organ_count", [](const PyStand& s) { return s.stand.organ_count(); })
      .def_property_readonly(
          "organs",
          [](py::object self) {
            PyStand& s = self.cast<PyStand&>();
            py::dtype dt = py::dtype::from_args(
                py::list(py::make_tuple(py::make_tuple("plant", "<i4"), py::make_tuple("parent", "<i4"),
                                        py::make_tuple("leaf", "<i4"), py::make_tuple("kind", "u1"),
                                        py::make_tuple("prototype", "u1"), py::make_tuple("lod", "u1"),
                                        py::make_tuple("reserved", "u1"))));
            return read_only(
                py::array(dt, std::vector<py::ssize_t>{static_cast<py::ssize_t>(s.stand.organ_count())},
                          std::vector<py::ssize_t>{static_cast<py::ssize_t>(sizeof(OrganRecord))},
                          s.stand.organs.data(), self));
          },
          "Structured array (plant, parent, leaf, kind, prototype, lod) viewing the stand's organ records "
          "(no copy; read-only).")
      .def_property_readonly(
          "transforms",
          [](py::object self) {
            PyStand& s = self.cast<PyStand&>();
            const auto n = static_cast<py::ssize_t>(s.stand.organ_count());
            return read_only(py::array_t<float>(
                {n, py::ssize_t{4}, py::ssize_t{3}},
                {static_cast<py::ssize_t>(sizeof(Affine3f)), py::ssize_t{12}, py::ssize_t{4}},
                reinterpret_cast<const float*>(s.stand.transforms.data()), self));
          },
          "float32 array (organs, 4, 3) viewing the plant-frame transforms: rows H*size, L*size, U*size, "
          "joint (read-only).")
      .def_property_readonly(
          "base_points",
          [](py::object self) {
            PyStand& s = self.cast<PyStand&>();
            const auto n = static_cast<py::ssize_t>(s.stand.organ_count());
            return read_only(py::array_t<float>(
                {n, py::ssize_t{3}}, {static_cast<py::ssize_t>(sizeof(Affine3f)), py::ssize_t{4}},
                reinterpret_cast<const float*>(s.stand.transforms.data()) + 9, self));
          },
          "float32 array (organs, 3) viewing each organ's base point (joint) in its plant's frame "
          "(read-only).")
      .def_property_readonly(
          "area",
          [](PyStand& s) {
            PrototypeLibrary lib;
            py::array_t<double> a(static_cast<py::ssize_t>(s.stand.organ_count()));
            auto* p = a.mutable_data();
            for (std::size_t i = 0; i < s.stand.organ_count(); ++i) p[i] = organ_area(s.stand, i, lib);
            return a;
          },
          "One-sided area of each organ, m2 (as organs.csv; computed).")
      .def_property_readonly(
          "length",
          [](PyStand& s) {
            PrototypeLibrary lib;
            py::array_t<double> a(static_cast<py::ssize_t>(s.stand.organ_count()));
            auto* p = a.mutable_data();
            for (std::size_t i = 0; i < s.stand.organ_count(); ++i) p[i] = organ_length(s.stand, i);
            return a;
          },
          "Length of each organ, m (as organs.csv; computed).")
      .def_property_readonly(
          "plants",
          [](PyStand& s) {
            py::dtype dt = py::dtype::from_args(py::list(
                py::make_tuple(py::make_tuple("x", "<f8"), py::make_tuple("y", "<f8"),
                               py::make_tuple("rotation", "<f8"), py::make_tuple("seed", "<u8"),
                               py::make_tuple("steps", "<i4"), py::make_tuple("organ_count", "<u4"))));
            py::array out(dt, std::vector<py::ssize_t>{static_cast<py::ssize_t>(s.stand.plant_count())});
            auto* b = static_cast<char*>(out.mutable_data());
            for (std::size_t i = 0; i < s.stand.plant_count(); ++i) {
              const PlantRecord& r = s.stand.plants[i];
              char* row = b + i * static_cast<std::size_t>(dt.itemsize());
              std::memcpy(row, &r.x, 8), std::memcpy(row + 8, &r.y, 8),
                  std::memcpy(row + 16, &r.rotation_deg, 8);
              std::memcpy(row + 24, &r.seed, 8);
              const std::int32_t st = r.steps;
              std::memcpy(row + 32, &st, 4), std::memcpy(row + 36, &r.organ_count, 4);
            }
            return out;
          },
          "Structured array of the plants (x, y, rotation, seed, steps, organ_count).")
      .def(
          "detect",
          [](PyStand& s, py::kwargs kwargs) {
            const StandInUse in_use(s, "Stand.detect");
            CLI::App app;
            cli::DetectOptions d;
            d.add_to(app);
            parse_keywords(app, "Stand.detect", {}, kwargs);
            const DetectRequest req = d.request();
            std::string note;
            Contacts c;
            std::string name, device;
            {
              py::gil_scoped_release nogil;
              const ThreadLimit thread_limit(d.threads);
              auto b = backend_named(d.backend, note);
              c = b->detect(s.stand, req);
              name = b->name(), device = b->device();
            }
            py::dict out;
            out["contacts"] = contacts_array(c.pairs);
            out["counts"] = json_to_py(cli::counts_json(c));
            out["backend"] = name;
            out["device"] = device;
            out["note"] = note;
            s.before = c;  // as canopy stand --no-resolve writes them
            s.after = std::move(c);
            return out;
          },
          "Detects contacts with canopy stand's detection options, read by its parser: level='exact', "
          "clearance=0, collide (every organ kind by default), backend='auto', threads=0, max_device_memory. "
          "Returns {'contacts': structured array, 'counts': per level, 'backend': name, 'device', 'note': "
          "how "
          "the backend was chosen}.")
      .def(
          "resolve",
          [](PyStand& s, py::object progress, py::kwargs kwargs) {
            const StandInUse in_use(s, "Stand.resolve");
            CLI::App app;
            cli::DetectOptions d;
            d.add_to(app);
            cli::ResolveOptions ro;
            ro.add_to(app);
            parse_keywords(app, "Stand.resolve", {}, kwargs,
                           {{"level", "resolve_level"},
                            {"candidates", "resolve_candidates"},
                            {"axes", "resolve_axes"},
                            {"step", "resolve_step"},
                            {"host_search", "resolve_host_search"},
                            {"device_search", "resolve_device_search"},
                            {"lanes", "resolve_lanes"},
                            {"stats", "resolve_stats"}});
            if (app.count("--no-resolve") > 0)
              throw std::invalid_argument("Stand.resolve: unknown option 'no_resolve'");
            ro.progress = false;
            const DetectRequest dreq = d.request();  // exact: what is left is counted exactly
            Callback cb(std::move(progress));
            ResolveResult r;
            Contacts before, after;
            std::string name, device, note;
            try {
              py::gil_scoped_release nogil;
              const ThreadLimit thread_limit(d.threads);
              auto b = backend_named(d.backend, note);
              before = b->detect(s.stand, dreq);
              DetectRequest at = dreq;
              at.level = ro.config().level;
              const Contacts start = at.level == dreq.level ? before : b->detect(s.stand, at);
              std::function<void(const ResolveProgress&)> hook;
              if (cb.set()) hook = [&](const ResolveProgress& p) { cb(p.round, p.contacts, p.seconds); };
              r = cli::run_resolution(s.stand, *b, dreq, ro, start, hook);
              after = b->detect(s.stand, dreq);
              name = b->name(), device = b->device();  // what ran to the end
            } catch (const CallbackRaised&) {
              cb.rethrow();
            }
            py::dict out = json_to_py(cli::resolution_json(r));
            out["contacts_after"] = contacts_array(after.pairs);
            out["backend"] = name;
            out["device"] = device;
            out["note"] = note;
            s.before = std::move(before);
            s.after = std::move(after);
            return out;
          },
          py::arg("progress") = py::none(),
          "Turns organs out of contact (canopy stand's resolution) with its options, read by its parser: "
          "level='exact' (--resolve-level), clearance, resolve_clearance=1e-4, collide, max_rounds=30, "
          "candidates, axes, step, bend_joints, bend_step, host_search, lanes, stats, backend='auto', "
          "threads=0, max_device_memory. progress(round, contacts_left, seconds) is called as each round "
          "goes on (several times while "
          "a long round is planned) and at its end, and "
          "raising from it stops the run. Returns report.json's 'resolution' (its 'planning' and 'search' "
          "say "
          "what planned the rounds) with 'contacts_after', 'backend', 'device' and 'note'.")
      .def(
          "export",
          [](PyStand& s, py::object dir_arg, py::object formats, bool glb_instancing, bool glb_compact) {
            const StandInUse in_use(s, "Stand.export");
            const std::string dir = path_of(dir_arg);
            cli::refuse_output_over_inputs(s.inputs, dir);  // as canopy stand: never over what it read
            // A list of formats, or one string "glb,ply" as canopy.stand and --formats take it.
            std::string list;
            if (py::isinstance<py::str>(formats)) list = formats.cast<std::string>();
            else
              for (const auto& f : formats.cast<std::vector<std::string>>())
                list += (list.empty() ? "" : ",") + f;
            if (list.empty()) throw std::invalid_argument("formats: give at least one of glb, obj, ply");
            const auto fs = cli::parse_formats(list);
            const cli::GlbForm glb = cli::glb_form(glb_instancing, glb_compact, 0);
            cli::check_glb_written(glb_instancing, glb_compact, list,
                                   {"glb_instancing", "glb_compact", "formats"});
            if (glb.compact && fs.count("glb")) check_glb_compact(ExportScope::whole(s.stand));
            py::gil_scoped_release nogil;
            const ThreadLimit thread_limit(0);  // refuses an OMP_NUM_THREADS past canopy's maximum
            PrototypeLibrary lib;
            // The folder's earlier stand is replaced as a set, as canopy stand does.
            OutputSet files(dir, cli::stand_folder_files(), cli::kStandFolderMarker);
            cli::write_stand_files(s.stand, lib, fs, glb, files);
            // canopy stand's contact tables: before the last resolution and after it (the last
            // detection both, as canopy stand --no-resolve writes them).
            if (s.before) write_contacts_csv(s.stand, *s.before, files.open("contacts.csv"));
            if (s.after) write_contacts_csv(s.stand, *s.after, files.open("contacts_after.csv"));
            files.commit_all();
          },
          py::arg("dir"), py::kw_only(), py::arg("formats") = py::str("glb"),
          py::arg("glb_instancing") = false, py::arg("glb_compact") = false,
          "Writes the stand's mesh files, organs.csv and plants.csv as canopy stand does, and its "
          "contacts.csv and contacts_after.csv after detect() (both that detection) or resolve() (before and "
          "after it); glb_compact writes stand.glb quantized (KHR_mesh_quantization, "
          "positions in steps "
          "of at most 50 um, half the default resolution clearance).");
}

}  // namespace canopy::python
