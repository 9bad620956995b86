#pragma once
/// `canopy stand` under mpirun (builds with MPI): the field split into one tile per rank, with
/// halos; the same files, byte for byte, as one process writes (timings and device aside).
#include "tools/stand_run.hpp"

namespace canopy::cli {

/// Every rank calls it with the same options; rank 0 prints the summary.
void run_stand_tiled(StandOptions o);

}  // namespace canopy::cli
