// Scaling of tiled runs over MPI: the default stand (docs/design.md: rows of 100 plants, 1.0 m x 0.4 m,
// random rotation, 0.02 m jitter, seed 1) grown, detected to the exact level and resolved by
// `mpirun -np P bench_scale`, exactly as `canopy stand` does under mpirun but without the files.
// Per size: plants per rank, the largest tile with its halo, seconds per stage (rank 0's; the
// stages end in collectives, so every rank ends them together), rounds, time in collectives
// during resolution (the slowest rank's, waits for other ranks included), and plants per second
// per rank. Weak scaling: compare P ranks on P x N plants with 1 rank on N; strong: the same N.
// Usage: mpirun -np P bench_scale [--sizes 10000,20000] [--backend cpu|cuda|auto] [--threads T]
//                                 [--grammar FILE] [--csv FILE] [--no-resolve] [--all-levels]
// Detection runs at the exact level only unless --all-levels (canopy stand's report counts every
// level up to the one asked for, one detection each).
#include "distributed/mpi_comm.hpp"
#include "geometry/split_list.hpp"
#include "tools/bench_usage.hpp"
#include "tools/process_memory.hpp"
#include "tools/stand_tiled.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

using namespace canopy;
using namespace canopy::cli;

namespace {

/// A comma-separated option's items, empty ones skipped.
std::vector<std::string> items(const std::string& s) {
  std::vector<std::string> v = split_list(s);
  std::erase(v, std::string());
  return v;
}

double timing(const StandReport& r, const char* key) {
  const auto it = r.timings.find(key);
  return it == r.timings.end() ? 0 : it->second;
}

}  // namespace

int main(int argc, char** argv) {
  canopy::keep_freed_memory();
  mpi::Session session;
  std::vector<std::string> sizes{"10000"};
  std::string backend = "auto", grammar = "grammars/tomato.yaml", csv = "bench/results/scale.csv";
  int threads = 0;
  bool resolve = true;
  bool all_levels = false;  // detect the exact level only (canopy stand also counts the levels below it)
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool value = i + 1 < argc;  // an option's value follows
    if (a == "--sizes" && value) sizes = items(argv[++i]);
    else if (a == "--backend" && value) backend = argv[++i];
    else if (a == "--threads" && value) threads = std::stoi(argv[++i]);
    else if (a == "--grammar" && value) grammar = argv[++i];
    else if (a == "--csv" && value) csv = argv[++i];
    else if (a == "--no-resolve") resolve = false;
    else if (a == "--all-levels") all_levels = true;
    else {
      return help_or_refuse(
          "bench_scale", argv[i],
          "usage: mpirun -np P bench_scale [--sizes 10000,20000] [--backend cpu|cuda|auto] [--threads T]\n"
          "                                [--grammar FILE] [--csv FILE] [--no-resolve] [--all-levels]\n",
          mpi::rank() == 0);
    }
  }
  const int rank = mpi::rank(), ranks = mpi::size();
  std::FILE* out = nullptr;
  if (rank == 0) {
    const bool fresh = !std::filesystem::exists(csv);
    out = std::fopen(csv.c_str(), "a");
    if (!out) {
      fmt::print(stderr, "bench_scale: cannot write {}\n", csv);
      mpi::abort("cannot write the CSV");
    }
    if (fresh)
      fmt::print(out,
                 "ranks,plants,plants_per_rank,largest_tile,organs,generate_s,detect_s,resolve_s,total_s,"
                 "rounds,comm_s,"
                 "comm_per_round_s,contacts_before,contacts_after,plants_per_s_per_rank,backend,device\n");
    fmt::print("{:>5} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>6} {:>8} {:>10} {:>9} {:>7} {:>12}\n",
               "ranks", "plants", "per rank", "tile", "grow s", "detect s", "resolve s", "total s", "rounds",
               "comm s", "comm/round", "before", "after", "plants/s/rank");
  }
  for (const std::string& size : sizes) {
    const int n = std::stoi(size);
    StandOptions o;
    o.grammar = grammar;
    o.rows.rows = n < 100 ? 1 : n / 100;
    o.rows.per_row = n < 100 ? n : 100;
    o.rows.row_spacing = 1.0;
    o.rows.plant_spacing = 0.4;
    o.rows.jitter = 0.02;
    o.rows.seed = 1;
    o.random_rotation = true;
    o.detect.backend = backend;
    o.detect.threads = threads;
    o.resolve.no_resolve = !resolve;
    o.resolve.progress = false;
    TiledStand ts = grow_detect_resolve_tiled(o, all_levels);
    const double comm = mpi::max(ts.comm_s);
    const auto largest = static_cast<std::size_t>(mpi::max(static_cast<double>(ts.tile.region.size())));
    std::int64_t own_organs = 0;
    for (std::uint32_t p : ts.scope->plants) own_organs += ts.tile.stand.plants[p].organ_count;
    const std::int64_t organs = mpi::sum({own_organs})[0];
    if (rank != 0) continue;
    const StandReport& r = ts.rep;
    const double total =
        timing(r, "generate") + timing(r, "detect") + timing(r, "resolve") + timing(r, "detect_after");
    const int rounds = ts.resolved ? ts.resolved->rounds : 0;
    const std::size_t before = ts.before.counts[3] ? ts.before.counts[3]->total() : 0;
    const std::size_t after = ts.resolved ? ts.resolved->contacts_after : before;
    const double rate = static_cast<double>(n) / total / ranks;
    const std::string device = r.device.is_string() ? r.device.get<std::string>() : std::string("cpu");
    fmt::print(
        "{:>5} {:>9} {:>9} {:>9} {:>9.2f} {:>9.2f} {:>9.2f} {:>9.2f} {:>6} {:>8.3f} {:>10.4f} {:>9} {:>7} "
        "{:>12.0f}\n",
        ranks, n, n / ranks, largest, timing(r, "generate"), timing(r, "detect"), timing(r, "resolve"), total,
        rounds, comm, rounds ? comm / rounds : 0.0, before, after, rate);
    if (ts.resolved)
      fmt::print("      resolution planned with: {} ({} on {})\n", ts.resolved->planning, r.backend, device);
    fmt::print(out, "{},{},{},{},{},{:.4f},{:.4f},{:.4f},{:.4f},{},{:.4f},{:.5f},{},{},{:.1f},{},\"{}\"\n",
               ranks, n, n / ranks, largest, organs, timing(r, "generate"), timing(r, "detect"),
               timing(r, "resolve"), total, rounds, comm, rounds ? comm / rounds : 0.0, before, after, rate,
               r.backend, device);
    std::fflush(out);
  }
  if (out) std::fclose(out);
  return 0;
}
