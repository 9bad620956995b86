// canopy stand: grow a stand from a grammar and a layout, detect, resolve, and write its files.
#include "geometry/prototype.hpp"
#include "tools/cli_common.hpp"
#include "tools/stand_run.hpp"
#ifdef CANOPY_WITH_MPI
#include "distributed/mpi_comm.hpp"
#include "tools/stand_tiled.hpp"
#endif

namespace canopy::cli {

Command add_stand(CLI::App& root) {
  auto o = std::make_shared<StandOptions>();
  CLI::App* app = root.add_subcommand("stand", "Grow a stand of plants from a grammar and write its files");
  app->add_option("GRAMMAR", o->grammar, "Grammar file (YAML)")->required();
  app->add_option("-o,--out", o->out, "Output folder (created if missing; default out)");
  app->add_option("--steps", o->steps, "Derivation steps for every plant (default: the grammar's)")
      ->transform(whole_in(0, kMaxSteps));
  app->add_option("--set", o->set, "Override a constant: NAME=VALUE (repeatable)");
  app->add_option("--lod", o->lod, "Level of detail of prototype meshes, 1 (coarse) to 16 (default 2)")
      ->transform(whole_in(1, kMaxLod));
  app->add_option("--formats", o->formats,
                  "Mesh formats to write, comma separated: glb,obj,ply (default glb)");
  app->add_flag(
      "--glb-instancing", o->glb_instancing,
      "Write stand.glb with one shared mesh per prototype drawn per organ (EXT_mesh_gpu_instancing): "
      "about 20 times smaller; organ ids become a per-instance _ORGAN attribute");
  app->add_flag(
      "--glb-compact", o->glb_compact,
      "Write stand.glb with quantized positions, normals, UVs and indices (KHR_mesh_quantization): about "
      "half "
      "the size; positions in steps below half the resolution clearance; organ id = the plant node's "
      "extras.first_organ + the _ORGAN attribute");
  app->add_option("--max-modules", o->max_modules, "Module cap per plant derivation")
      ->transform(whole_in(1, INT64_MAX));
  o->detect.add_to(*app);
  o->resolve.add_to(*app);
  auto* layout = app->add_option_group("layout",
                                       "Rows (each option given overrides that field of the grammar's stand "
                                       "entry; the others keep the entry's) or a "
                                       "positions file");
  layout->add_option("--rows", o->rows.rows, "Number of rows (along +X, spaced along +Y)")
      ->transform(whole_in(1, INT32_MAX));
  layout->add_option("--per-row", o->rows.per_row, "Plants per row")->transform(whole_in(1, INT32_MAX));
  layout
      ->add_option("--row-spacing", o->rows.row_spacing,
                   "Metres between rows (default: the grammar's stand entry, else 1.0)")
      ->check(kFinite)
      ->check(at_least(0));
  layout
      ->add_option("--plant-spacing", o->rows.plant_spacing,
                   "Metres between plants in a row (default: the grammar's stand entry, else 0.4)")
      ->check(kFinite)
      ->check(at_least(0));
  layout
      ->add_option("--double-rows", o->rows.double_rows,
                   "Rows in pairs GAP metres apart; pairs --row-spacing apart")
      ->check(kFinite)
      ->check(at_least(0));
  layout->add_option("--jitter", o->rows.jitter, "Radius in metres of a uniform disc around each position")
      ->check(kFinite)
      ->check(at_least(0));
  layout->add_flag("--random-rotation", o->random_rotation, "Turn each plant by a random angle about Z");
  layout->add_flag("--no-random-rotation", o->no_random_rotation,
                   "Every plant facing the same way (overrides the grammar's stand entry)");
  layout
      ->add_option("--seed", o->rows.seed,
                   "Stand seed: plant seeds, jitter and rotations derive from it (default: the grammar's "
                   "stand entry, else 1)")
      ->transform(kSeed);
  layout->add_option("--positions", o->positions,
                     "CSV with columns x,y,rotation,seed and optional grammar,steps");
  add_target_options(*app, o->target);
  app->add_flag("--any-grammar-path", o->any_grammar_path,
                "Let a positions file's grammar cells name any file (an absolute path, or '..' above the "
                "positions file's folder)");
  return {app, [o]() {
#ifdef CANOPY_WITH_MPI
            if (mpi::launched()) {
              if (o->target.set())
                throw std::invalid_argument(
                    "--target-lai and --target-ground-cover: not under mpirun (run them in one process)");
              run_stand_tiled(*o);
              return 0;
            }
#endif
            o->ends_process = true;  // canopy's main ends it (tools/process_end.hpp)
            run_stand(*o);
            return 0;
          }};
}

}  // namespace canopy::cli
