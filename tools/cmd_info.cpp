// canopy info: version, the detection backends this build and machine offer, and the renderer.
#include "tools/cli_common.hpp"
#include "tools/heap_pages.hpp"
#include "tools/process_rerun.hpp"

#include <fmt/format.h>

#include <stdexcept>
#include <string>
#ifdef CANOPY_HAVE_CUDA
#include "cuda/device.hpp"
#endif
#ifdef CANOPY_WITH_MPI
#include "distributed/mpi_comm.hpp"
#endif

namespace canopy::cli {

Command add_info(CLI::App& root) {
  CLI::App* app = root.add_subcommand("info", "Print the version and the detection backends available here");
  auto self_test = std::make_shared<bool>(false);
  app->add_flag("--self-test", *self_test, "Run a small kernel on each CUDA device and check its result");
  return {
      app, [self_test]() {
        fmt::print(
            "canopy {}\nheap pages: {} (tools/heap_pages.hpp; CANOPY_HEAP_PAGES=large|small)\nbackend cpu: "
            "available\n",
            CANOPY_VERSION, heap_pages_in_use());
        fmt::print("openmp waits: {} (tools/process_rerun.hpp)\n", waits_described());
#ifdef CANOPY_HAVE_CUDA
        const auto report = cuda::query_devices();
        if (report.devices.empty())
          fmt::print("backend cuda: built, no device ({})\n", report.unavailable_reason);
        for (const auto& d : report.devices) {
          fmt::print("backend cuda: device {} {} (sm_{}{}, {:.1f} GiB, {} SMs)\n", d.index, d.name, d.major,
                     d.minor, static_cast<double>(d.memory_bytes) / (1u << 30), d.multiprocessors);
          if (*self_test) {
            cuda::self_test(d.index);
            fmt::print("  self test passed\n");
          }
        }
#else
            fmt::print("backend cuda: not built\n");
#endif
        // A self-test asked for and not run is a failure, not a silence that reads as a pass.
        std::string untested;
#ifdef CANOPY_HAVE_CUDA
        if (*self_test && report.devices.empty())
          untested = fmt::format("no CUDA device to test ({})", report.unavailable_reason);
#else
            if (*self_test) untested = "this build has no CUDA backend";
#endif
#ifdef CANOPY_HAVE_EMBREE
        fmt::print("render: Embree (canopy render)\n");
#else
            fmt::print("render: not built (Embree or libpng missing)\n");
#endif
#ifdef CANOPY_WITH_MPI
        fmt::print("mpi: {} (tiled runs: mpirun -np P canopy stand|sweep ...){}\n", mpi::library_version(),
                   mpi::launched() ? fmt::format("; this is rank {} of {}", mpi::rank(), mpi::size()) : "");
#else
            fmt::print("mpi: not built (tiled runs need OpenMPI: libopenmpi-dev)\n");
#endif
        if (!untested.empty()) throw std::runtime_error("--self-test: " + untested);
        return 0;
      }};
}

}  // namespace canopy::cli
