// canopy stand: grow a stand from a grammar and a layout, detect, resolve, and write its files.
#include "geometry/prototype.hpp"
#include "tools/cli_common.hpp"
#include "tools/stand_options.hpp"
#include "tools/stand_run.hpp"
#ifdef CANOPY_WITH_MPI
#include "distributed/mpi_comm.hpp"
#include "tools/stand_tiled.hpp"
#endif

namespace canopy::cli {

std::shared_ptr<StandOptions> register_stand(CLI::App& app) {
  auto o = std::make_shared<StandOptions>();
  app.add_option("GRAMMAR", o->grammar, "Grammar file (YAML)")->required();
  app.add_option("-o,--out", o->out, "Output folder (created if missing; default out)");
  add_grow_options(app, *o);
  add_file_options(app, *o);
  o->detect.add_to(app);
  o->resolve.add_to(app);
  return o;
}

Command add_stand(CLI::App& root) {
  CLI::App* app = root.add_subcommand("stand", "Grow a stand of plants from a grammar and write its files");
  auto o = register_stand(*app);
  return {app, [o]() {
#ifdef CANOPY_WITH_MPI
            if (mpi::launched()) {
              if (o->target.set() || o->target.error)
                throw std::invalid_argument(
                    "--target-lai, --target-ground-cover and --target-error: not under mpirun (run them in "
                    "one "
                    "process)");
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
