#pragma once
/// `canopy stand` under mpirun (builds with MPI): the field split into one tile per rank, with
/// halos; the same files, byte for byte, as one process writes (timings and device aside).
#include "distributed/mpi_files.hpp"
#include "distributed/tiles.hpp"
#include "tools/stand_run.hpp"

#include <chrono>
#include <memory>
#include <optional>

namespace canopy::cli {

/// A rank's part of the stand: the plants it holds (its own and its halo), their global ids and
/// the shifts from local to global organ and leaf ids.
struct Tile {
  std::vector<std::uint32_t> region;      // global plant ids, ascending
  std::vector<std::uint8_t> owned;        // per local plant
  std::vector<std::int64_t> first_organ;  // per global plant (size N + 1)
  std::vector<std::int64_t> first_leaf;
  std::vector<std::vector<int>> holders;  // per local plant: the other ranks holding it
  Stand stand;

  std::size_t local_of(std::int64_t global_plant) const {
    return static_cast<std::size_t>(
        std::lower_bound(region.begin(), region.end(), static_cast<std::uint32_t>(global_plant)) -
        region.begin());
  }
};

/// A tiled stand grown, detected and resolved on every rank (before its files are written).
struct TiledStand {
  std::set<std::string> formats;
  StandPlan plan;
  std::unique_ptr<DetectionBackend> backend;
  std::string backend_note;
  std::vector<PlantPlacement> placements;  // the whole stand's
  Tiling tiling;
  Tile tile;
  double reach = 0, hop = 0, halo = 0;  // swept reach, farthest meeting distance, halo depth (metres)
  std::vector<std::int64_t> ids;        // global ids of this rank's own plants
  std::unique_ptr<mpi::RankScan> scan;
  std::unique_ptr<ExportScope> scope;  // this rank's own plants
  StandReport rep;
  Contacts before, after;  // counts of the whole stand, pairs this rank owns
  std::optional<ResolveResult> resolved;
  double comm_s = 0;  // resolution: time in collectives (waits included)
  std::chrono::steady_clock::time_point start;
};

/// Collective: everything of `canopy stand` under mpirun but the files. `lower_levels` false
/// detects the asked level only (its counts alone; report.json counts every level up to it).
TiledStand grow_detect_resolve_tiled(StandOptions& o, bool lower_levels = true);

/// Every rank calls it with the same options; rank 0 prints the summary.
void run_stand_tiled(StandOptions o);

}  // namespace canopy::cli
