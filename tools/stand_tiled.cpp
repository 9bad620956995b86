// canopy stand under mpirun: the field in tiles with halos (distributed/tiles), detection of the
// contacts each rank owns, resolution in lockstep with turns traded across tile borders, and one
// set of files written by every rank (distributed/mpi_files), byte-identical to one process.
//
// Why the halo is three hops deep: a turn of an owned organ is planned from the contacts of its
// plant and of the plants it touches (one hop), from their candidate movers' contacts and
// surroundings (two hops) and, for the last-resort pass, from whether those movers were already
// claimed, which the contacts of plants two hops out decide (three hops). A hop is the farthest
// two plant bounds can reach to meet: 2 sqrt(2) x the largest swept reach (plant bounds are
// vertical-axis boxes around the swept disc) plus both clearances. Only the contacts of plants
// within one hop are planned (they make every decision an own turn depends on); the rest of the
// halo supplies their candidates' contacts and surroundings.
#include "resolution/swept_reach.hpp"
#include "tools/json_text.hpp"
#include "distributed/mpi_comm.hpp"
#include "distributed/mpi_files.hpp"
#include "distributed/region.hpp"
#include "distributed/tiles.hpp"
#include "geometry/clock.hpp"
#include "geometry/export.hpp"
#include "geometry/thread_limit.hpp"
#include "tools/cli_common.hpp"
#include "tools/stand_run.hpp"
#include "tools/stand_tiled.hpp"
#include "tools/tile_trade.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace canopy::cli {
namespace {

/// Runs `work` on every rank; when it throws on any, every rank throws the first failure.
template <typename F>
void on_every_rank(F&& work) {
  std::string error;
  try {
    work();
  } catch (const std::exception& e) {
    error = e.what();
    if (error.empty()) error = "unknown error";
  }
  mpi::agree(error);
}

}  // namespace

TiledStand grow_detect_resolve_tiled(StandOptions& o, bool lower_levels) {
  TiledStand ts;
  const auto t_start = std::chrono::steady_clock::now();
  const int rank = mpi::rank(), ranks = mpi::size();
  std::set<std::string>& formats = ts.formats;
  StandPlan& plan = ts.plan;
  DetectRequest dreq;
  std::unique_ptr<DetectionBackend>& backend = ts.backend;
  std::string& backend_note = ts.backend_note;
  std::vector<PlantPlacement>& placements = ts.placements;
  on_every_rank([&] {
    formats = parse_formats(o.formats);
    if (o.glb_instancing)
      throw std::invalid_argument("--glb-instancing is written by one process only; run it without mpirun");
    plan = plan_stand(o);
    refuse_output_over_inputs(plan_inputs(plan, o), o.out);
    if (rank == 0) print_notes(plan.grammar.notes);
    dreq = o.detect.request();
    backend = make_backend(o.detect.backend, backend_note, mpi::local_rank());
    if (rank == 0) check_output_dir(o.out);  // made only once the files are complete
    placements = o.positions.empty() ? row_layout(plan.layout) : plan.request.plants;
  });
  const std::size_t n = placements.size();
  ts.tiling = make_tiling(placements, ranks);
  const Tiling& tiling = ts.tiling;
  const ResolveConfig rc = o.resolve.config();
  StandReport& rep = ts.rep;
  Tile& t = ts.tile;

  // Own plants first: their swept reach sizes every rank's halo, their organ and leaf counts
  // number the whole stand.
  const auto t_grow = std::chrono::steady_clock::now();
  double& reach = ts.reach;
  std::vector<std::int64_t> own_counts;  // global id, organs, leaves per own plant
  std::vector<std::uint32_t> own;
  Stand mine;
  on_every_rank([&] {
    GrowRequest req = plan.request;
    req.plants.clear();
    for (std::size_t p = 0; p < n; ++p)
      if (tiling.owner[p] == rank)
        own.push_back(static_cast<std::uint32_t>(p)), req.plants.push_back(placements[p]);
    if (!req.plants.empty()) check_plan_fits(plan, 3 * own.size());
    mine = grow_stand(req);
    PrototypeLibrary lib;
    for (std::size_t p = 0; p < mine.plant_count(); ++p) {
      reach = std::max(reach, swept_reach(mine, lib, p, rc.movable));
      own_counts.insert(own_counts.end(), {static_cast<std::int64_t>(own[p]),
                                           static_cast<std::int64_t>(mine.plants[p].organ_count),
                                           static_cast<std::int64_t>(mine.plants[p].leaf_count)});
    }
  });
  reach = mpi::max(reach);
  {
    const std::vector<std::int64_t> all = mpi::allgather(own_counts);
    t.first_organ.assign(n + 1, 0);
    t.first_leaf.assign(n + 1, 0);
    for (std::size_t i = 0; i < all.size(); i += 3) {
      t.first_organ[static_cast<std::size_t>(all[i]) + 1] = all[i + 1];
      t.first_leaf[static_cast<std::size_t>(all[i]) + 1] = all[i + 2];
    }
    for (std::size_t p = 0; p < n; ++p)
      t.first_organ[p + 1] += t.first_organ[p], t.first_leaf[p + 1] += t.first_leaf[p];
  }
  const double clearance = std::max(o.detect.clearance, rc.clearance);
  ts.hop = 2 * std::sqrt(2.0) * reach + 2 * clearance + 1e-3 * (1 + reach);
  ts.halo = 3 * ts.hop;
  const double halo = ts.halo;
  t.region = tile_region(tiling, placements, rank, halo);
  on_every_rank([&] {
    // The halo plants, grown now, joined to the own plants grown above.
    GrowRequest req = plan.request;
    req.plants.clear();
    std::vector<std::uint32_t> halo_ids;
    for (std::uint32_t g : t.region)
      if (tiling.owner[g] != rank) halo_ids.push_back(g), req.plants.push_back(placements[g]);
    const Stand halo_stand = grow_stand(req);
    t.stand = merge_region(mine, own, halo_stand, halo_ids);
    mine = Stand{};
    if (n > 0)
      t.stand.stand_origin = {placements[0].x, placements[0].y, 0};  // the whole stand's, not the tile's
    for (std::uint32_t g : t.region) {
      t.owned.push_back(tiling.owner[g] == rank ? 1 : 0);
      t.holders.push_back(t.owned.back() ? tiles_holding(tiling, placements, g, halo) : std::vector<int>{});
    }
  });
  rep.timings["generate"] = seconds_since(t_grow);

  std::vector<std::int64_t>& ids = ts.ids;
  for (std::size_t p = 0; p < t.region.size(); ++p)
    if (t.owned[p]) ids.push_back(t.region[p]);
  ts.scan = std::make_unique<mpi::RankScan>(ids, n);
  ts.scope = std::make_unique<ExportScope>(owned_scope(t, *ts.scan));
  const ExportScope& scope = *ts.scope;

  // Detection and resolution: collective throughout, so a failure here ends every rank.
  Contacts& before = ts.before;
  Contacts& after = ts.after;
  std::optional<ResolveResult>& resolved = ts.resolved;
  try {
    const auto t_detect = std::chrono::steady_clock::now();
    Contacts full;
    before = detect_owned(*backend, t, dreq, dreq.level, lower_levels, &full);
    rep.timings["detect"] = seconds_since(t_detect);
    rep.contacts_before = counts_json(before);
    after = before;
    if (!o.resolve.no_resolve) {
      const auto t_resolve = std::chrono::steady_clock::now();
      DetectRequest at = dreq;
      at.level = rc.level;
      if (dreq.level != rc.level) full = backend->detect(t.stand, at);
      ResolvePartition part;
      part.owned = t.owned;
      for (std::uint32_t g : t.region)  // the plants within one hop of this strip
        part.plan.push_back(std::abs(ts.tiling.coordinate(ts.placements[g]) -
                                     std::clamp(ts.tiling.coordinate(ts.placements[g]),
                                                ts.tiling.lo[static_cast<std::size_t>(rank)],
                                                ts.tiling.hi[static_cast<std::size_t>(rank)])) <= ts.hop);
      // Time in the collectives (waiting for the slowest rank included).
      const auto timed = [&ts](auto&& f) {
        const auto t0 = std::chrono::steady_clock::now();
        auto r = f();
        ts.comm_s += seconds_since(t0);
        return r;
      };
      part.sum = [timed](std::vector<std::int64_t> v) {
        return timed([&] { return mpi::sum(std::move(v)); });
      };
      part.max = [timed](double v) { return timed([&] { return mpi::max(v); }); };
      part.exchange = [timed, &t](const std::vector<Turn>& mine) {
        return timed([&] { return exchange_turns(t, mine); });
      };
      ResolveOptions ro = o.resolve;
      ro.progress = ro.progress && rank == 0;
      resolved = run_resolution(t.stand, *backend, dreq, ro, full, {}, &part);
      resolved->unresolved = gather_unresolved(scope, resolved->unresolved);
      rep.timings["resolve"] = seconds_since(t_resolve);
      const auto t_check = std::chrono::steady_clock::now();
      after = detect_owned(*backend, t, dreq, dreq.level, lower_levels);
      rep.timings["detect_after"] = seconds_since(t_check);
      rep.resolution = resolution_json(*resolved);
    } else {
      rep.resolution = resolution_not_run_json(before);
    }
    rep.contacts_after = counts_json(after);
    rep.backend = backend->name();  // what ran to the end (auto may have fallen back)
    rep.device = backend->device();
    rep.backend_choice = backend_note;
  } catch (const std::exception& e) {
    mpi::abort(e.what());
  }
  ts.start = t_start;
  return ts;
}

void run_stand_tiled(StandOptions o) {
  const ThreadLimit thread_limit(o.detect.threads);
  TiledStand ts = grow_detect_resolve_tiled(o);
  const int rank = mpi::rank(), ranks = mpi::size();
  const std::size_t n = ts.placements.size();
  const Tile& t = ts.tile;
  const ExportScope& scope = *ts.scope;
  StandReport& rep = ts.rep;
  // The files: every rank its own plants' chunks, rank 0 the fixed text and the report.
  const auto t_export = std::chrono::steady_clock::now();
  PrototypeLibrary lib;
  StandCounts counts;
  counts.stand_origin = t.stand.stand_origin;
  {
    std::vector<std::int64_t> tris;
    const std::vector<std::size_t> local = triangles_per_plant(t.stand, lib);
    for (std::uint32_t p : scope.plants)
      tris.insert(tris.end(), {static_cast<std::int64_t>(t.region[p]), static_cast<std::int64_t>(local[p])});
    const std::vector<std::int64_t> all = mpi::allgather(tris);
    counts.triangles.assign(n, 0);
    counts.organs.assign(n, 0);
    for (std::size_t i = 0; i < all.size(); i += 2)
      counts.triangles[static_cast<std::size_t>(all[i])] = static_cast<std::size_t>(all[i + 1]);
    for (std::size_t p = 0; p < n; ++p)
      counts.organs[p] = static_cast<std::size_t>(t.first_organ[p + 1] - t.first_organ[p]);
  }
  {
    // The leaf angles of the owned plants, gathered and summed in plant order as one process does.
    struct Owned {
      std::int64_t plant;
      LeafAngleSums sums;
    };
    const std::vector<LeafAngleSums> local = leaf_angle_sums(t.stand, lib);
    std::vector<Owned> mine;
    for (std::uint32_t p : scope.plants) mine.push_back({static_cast<std::int64_t>(t.region[p]), local[p]});
    std::vector<LeafAngleSums> per_plant(n);
    for (const Owned& x : mpi::allgather(mine)) per_plant[static_cast<std::size_t>(x.plant)] = x.sums;
    rep.leaf_angles = leaf_angles_json(leaf_angles(per_plant));
  }
  mpi::SharedOutputSet files(o.out, stand_folder_files(), kStandFolderMarker, ts.ids, n);
  try {
    write_stand_files(
        scope, lib, ts.formats, [&](const std::string& name) -> ChunkWriter& { return files.open(name); },
        glb_form(o));
    write_contacts_csv(scope, ts.before.pairs, ts.before.level, files.open("contacts.csv"));
    write_contacts_csv(scope, ts.after.pairs, ts.after.level, files.open("contacts_after.csv"));
    rep.timings["export"] = seconds_since(t_export);
    describe_run(rep, o, ts.formats, ts.plan);
    rep.timings["total"] = seconds_since(ts.start);
    files.open("report.json").root_text(json_text(report_json(counts, rep), 2) + "\n");
  } catch (const std::exception& e) {
    // The files are written collectively: a rank that fails part way cannot wait for the others.
    files.remove_temporaries();
    mpi::abort(e.what());
  }
  files.commit_all();
  if (rank == 0) {
    print_folder_changes(*files.folder(), files.committed());
    print_summary(counts, rep, o.out);
    if (o.positions.empty()) fmt::print("{}\n", layout_line(ts.plan.layout, ts.plan.layout_sources));
    fmt::print("tiles: {} ranks, strips across {}, halo {:.2f} m (swept reach {:.3f} m); {} plants here\n",
               ranks, ts.tiling.axis == 0 ? "x" : "y", ts.halo, ts.reach, t.region.size());
    print_contacts_table(ts.before, ts.backend_note);
    if (ts.resolved) print_resolution(*ts.resolved);
  }
}

}  // namespace canopy::cli
