#include "lsystem/grow.hpp"

#include "geometry/available_memory.hpp"
#include "geometry/clock.hpp"
#include "geometry/large_pages.hpp"
#include "geometry/prototype.hpp"
#include "geometry/thread_limit.hpp"
#include "lsystem/turtle.hpp"

#include <atomic>
#include <exception>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <omp.h>
#include <stdexcept>

namespace canopy {
namespace {

/// Plant p's organs before placement, and what its grammar said of it.
struct GrownPlant {
  TurtleResult turtle;
  int grammar = 0;
  int steps = 0;
  std::size_t modules = 0;
};

Affine3f rotate_z(const Affine3f& m, double deg) {
  const double a = deg * std::numbers::pi / 180;
  const float c = static_cast<float>(std::cos(a)), s = static_cast<float>(std::sin(a));
  const auto r = [&](Vec3f v) { return Vec3f{c * v.x - s * v.y, s * v.x + c * v.y, v.z}; };
  return {r(m.c0), r(m.c1), r(m.c2), r(m.t)};
}

/// What a grown plant takes until the stand is placed: its turtle's organs and the stand's
/// arrays for them, beside its placement and record.
double plant_need(const GrownPlant& gp) {
  const std::size_t per_organ =
      sizeof(Affine3f) + sizeof(OrganRecord) + 2 * sizeof(float) + sizeof(float) + sizeof(OrganInstance);
  return static_cast<double>((gp.turtle.organs.size() + 1) * per_organ + gp.modules * 10) +
         sizeof(PlantPlacement) + sizeof(PlantRecord);
}

void check_fits(const GrownPlant& first, std::size_t n, std::size_t memory_limit) {
  const double need = static_cast<double>(n) * plant_need(first);
  const std::size_t limit = memory_limit ? memory_limit : available_memory();
  if (limit && need > static_cast<double>(limit))
    throw std::runtime_error(fmt::format(
        "a stand of {} plants needs about {} ({} organs per plant), more than the {} available; "
        "use fewer plants or a coarser --lod",
        n, memory_text(need), first.turtle.organs.size(), memory_text(static_cast<double>(limit))));
}

/// The grammar a placement names; a file that cannot be opened is reported with the positions
/// file's line that names it.
Grammar load_placement_grammar(const GrowRequest& req, const PlantPlacement& pl) {
  try {
    return load_grammar(grammar_path(req, pl.grammar), req.load);
  } catch (const GrammarError& e) {
    // A file that cannot be used as a whole (missing, a folder, a device): its place is the line
    // that names it. An error at a line of the grammar itself names that line already.
    if (pl.grammar.empty() || pl.source_line <= 0 || req.positions_file.empty() || e.pos().line > 0) throw;
    const std::string message = fmt::format("{} (named by {}:{}, column 'grammar': '{}')", e.message(),
                                            req.positions_file, pl.source_line, pl.grammar);
    if (dynamic_cast<const GrammarFileError*>(&e)) throw GrammarFileError(e.pos(), message);
    throw GrammarError(e.pos(), message);
  }
}

/// Derives, interprets and runs the turtle for plant `index` (its `steps` already chosen).
void grow_plant(const Grammar& g, const PlantPlacement& pl, const GrowRequest& req, std::size_t index,
                GrownPlant& out) {
  const DeriveRequest dreq{out.steps, pl.seed, req.max_modules};
  const ModuleString s = derive(g, dreq);
  TurtleConfig tc;
  tc.lod = req.lod;
  tc.where = fmt::format("plant {} (seed {})", index, pl.seed);
  try {
    if (g.interpretation.empty()) {  // no copy of the string when there is nothing to interpret
      out.modules = s.size();
      out.turtle = run_turtle(g, s, tc);
    } else {
      const ModuleString t = interpret(g, s, pl.seed, req.max_modules);
      out.modules = t.size();
      out.turtle = run_turtle(g, t, tc);
    }
  } catch (const TurtleError& e) {
    // Every grammar error names file, line and column: the place that wrote the module (or its
    // parameter), found by deriving again while tracking where each module came from.
    if (const auto pos = module_source(g, dreq, true, e.module(), e.parameter()))
      throw GrammarError(*pos, e.detail());
    throw;
  }
}

}  // namespace

std::string grammar_path(const GrowRequest& req, const std::string& name) {
  if (name.empty()) return req.grammar;
  if (!req.relative_to.empty() && std::filesystem::path(name).is_relative())
    return (std::filesystem::path(req.relative_to) / name).string();
  return name;
}

void check_stand_fits(const GrowRequest& req, std::size_t plants) {
  if (req.plants.empty()) return;
  const PlantPlacement& pl = req.plants[0];
  const Grammar g = load_placement_grammar(req, pl);
  GrownPlant first;
  first.steps = pl.steps.value_or(req.steps.value_or(g.steps));
  grow_plant(g, pl, req, 0, first);
  check_fits(first, plants, req.memory_limit);
}

std::size_t available_memory() { return memory_available(); }

Stand grow_stand(const GrowRequest& req, GrowTimings* timings) {
  Stand stand;
  // Each grammar file is loaded once.
  std::map<std::string, int> index;
  std::vector<std::unique_ptr<Grammar>> grammars;
  auto grammar_index = [&](const PlantPlacement& pl) {
    const std::string& name = pl.grammar;
    const std::string path = grammar_path(req, name);
    // plants.csv names each plant's grammar in a cell of its line (geometry/export_csv.cpp).
    if (path.find_first_of("\n\r") != std::string::npos) {
      std::string shown;  // on the message's one line
      for (char c : path) shown += c == '\n' ? "\\n" : c == '\r' ? "\\r" : std::string(1, c);
      throw std::invalid_argument(fmt::format(
          "the grammar file's path holds a line break, which plants.csv cannot record: rename it ('{}')",
          shown));
    }
    auto it = index.find(path);
    if (it != index.end()) return it->second;
    grammars.push_back(std::make_unique<Grammar>(load_placement_grammar(req, pl)));
    stand.grammars.push_back(name.empty() ? req.grammar : name);
    return index[path] = static_cast<int>(grammars.size() - 1);
  };
  const std::size_t n = req.plants.size();
  // Every entry point (the command line, a positions file, the Python module) comes through here.
  if (req.lod < 1 || req.lod > kMaxLod)
    throw std::invalid_argument(
        fmt::format("the level of detail must lie in 1..{} (got {})", kMaxLod, req.lod));
  const int threads = checked_threads(req.threads);
  if (req.steps && (*req.steps < 0 || *req.steps > kMaxSteps))
    throw std::invalid_argument(
        fmt::format("the derivation steps must lie in 0..{} (got {})", kMaxSteps, *req.steps));
  for (std::size_t p = 0; p < n; ++p) {
    const PlantPlacement& pl = req.plants[p];
    if (pl.steps && (*pl.steps < 0 || *pl.steps > kMaxSteps))
      throw std::invalid_argument(
          fmt::format("plant {}: its derivation steps must lie in 0..{} (got {})", p, kMaxSteps, *pl.steps));
    if (!std::isfinite(pl.x) || !std::isfinite(pl.y) || !std::isfinite(pl.rotation_deg))
      throw std::invalid_argument(fmt::format(
          "plant {}: its position and rotation must be finite numbers (got x {}, y {}, rotation {})", p, pl.x,
          pl.y, pl.rotation_deg));
    if (std::fabs(pl.x) > kMaxPlantCoordinate || std::fabs(pl.y) > kMaxPlantCoordinate)
      throw std::invalid_argument(
          fmt::format("plant {}: its position (x {:g}, y {:g}) is farther from the origin than "
                      "the {:g} m plants may stand",
                      p, pl.x, pl.y, kMaxPlantCoordinate));
  }
  std::vector<GrownPlant> grown(n);
  for (std::size_t p = 0; p < n; ++p) {
    grown[p].grammar = grammar_index(req.plants[p]);
    const Grammar& g = *grammars[static_cast<std::size_t>(grown[p].grammar)];
    grown[p].steps = req.plants[p].steps.value_or(req.steps.value_or(g.steps));
  }

  std::vector<std::exception_ptr> errors(n);
  auto grow_one = [&](std::size_t p) {
    grow_plant(*grammars[static_cast<std::size_t>(grown[p].grammar)], req.plants[p], req, p, grown[p]);
  };

  const double t0 = now_seconds();
  const std::size_t limit = req.memory_limit ? req.memory_limit : available_memory();
  if (n > 0) {
    grow_one(0);
    check_fits(grown[0], n, limit);
  }
  // The first plant speaks for the others only where they are alike: plants of other seeds, ages
  // or grammars may be far larger. What the plants grown so far need is summed as they grow; past
  // the memory available the growth stops (the stand would not fit whatever the others need).
  std::atomic<double> need{n > 0 ? plant_need(grown[0]) : 0.0};
  std::atomic<std::size_t> organs_grown{n > 0 ? grown[0].turtle.organs.size() : 0}, plants_grown{n > 0};
  std::atomic<bool> outgrown{false};
#pragma omp parallel for schedule(dynamic, 4) num_threads(threads)
  for (std::size_t p = 1; p < n; ++p) {
    if (outgrown.load(std::memory_order_relaxed)) continue;
    try {
      grow_one(p);
      const double mine = plant_need(grown[p]);
      const double now = need.fetch_add(mine, std::memory_order_relaxed) + mine;
      organs_grown.fetch_add(grown[p].turtle.organs.size(), std::memory_order_relaxed);
      plants_grown.fetch_add(1, std::memory_order_relaxed);
      if (limit && now > static_cast<double>(limit)) outgrown = true;
    } catch (...) {
      errors[p] = std::current_exception();
    }
  }
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);  // the first failing plant, in plant order, as it was thrown
  if (outgrown)
    throw std::runtime_error(fmt::format(
        "a stand of {} plants needs more than the {} available: {} of them, grown, need about {} "
        "({} organs; the first plant has {}, the others are larger); use fewer plants, fewer steps or a "
        "coarser --lod",
        n, memory_text(static_cast<double>(limit)), plants_grown.load(), memory_text(need.load()),
        organs_grown.load(), grown[0].turtle.organs.size()));
  const double t1 = now_seconds();

  // Place: global ids plant by plant, then in string order.
  std::size_t organs = 0;
  for (const auto& gp : grown) organs += gp.turtle.organs.size();
  // The arrays in huge pages where the system offers them: resize() zeroes them on this thread,
  // which in 4 KiB pages took 0.6 s of a 10,000-plant stand's 2.0 s growth on the 2-core VM
  // (0.06 s in huge pages; canopy stand --no-resolve at 10,000 plants).
  const auto sized = [organs](auto& v) {
    v.reserve(organs);
    advise_large_pages(v.data(), organs * sizeof(v[0]));
    v.resize(organs);
  };
  sized(stand.transforms);
  sized(stand.organs);
  sized(stand.params);
  sized(stand.joint_limit_deg);
  stand.plants.resize(n);
  std::uint32_t first = 0, first_leaf = 0;
  for (std::size_t p = 0; p < n; ++p) {
    const PlantPlacement& pl = req.plants[p];
    PlantRecord& pr = stand.plants[p];
    pr.x = pl.x;
    pr.y = pl.y;
    pr.rotation_deg = pl.rotation_deg;
    pr.seed = pl.seed;
    pr.grammar = grown[p].grammar;
    pr.steps = grown[p].steps;
    pr.first_organ = first;
    pr.organ_count = static_cast<std::uint32_t>(grown[p].turtle.organs.size());
    pr.first_leaf = first_leaf;
    pr.leaf_count = static_cast<std::uint32_t>(grown[p].turtle.leaf_count);
    first += pr.organ_count;
    first_leaf += pr.leaf_count;
  }
#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::size_t p = 0; p < n; ++p) {
    const PlantRecord& pr = stand.plants[p];
    const auto& src = grown[p].turtle.organs;
    for (std::size_t k = 0; k < src.size(); ++k) {
      const OrganInstance& o = src[k];
      const std::size_t id = pr.first_organ + k;
      stand.transforms[id] = rotate_z(o.transform, pr.rotation_deg);
      OrganRecord& r = stand.organs[id];
      r.plant = static_cast<std::int32_t>(p);
      r.parent = o.parent < 0 ? -1 : static_cast<std::int32_t>(pr.first_organ) + o.parent;
      r.leaf = o.leaf < 0 ? -1 : static_cast<std::int32_t>(pr.first_leaf) + o.leaf;
      r.kind = o.kind;
      r.prototype = o.prototype;
      r.lod = static_cast<std::uint8_t>(o.lod);
      r.shape = o.shape;
      stand.params[id] = {o.params[0], o.params[1]};
      stand.joint_limit_deg[id] = o.joint_limit_deg;
    }
  }
  if (n > 0) stand.stand_origin = {stand.plants[0].x, stand.plants[0].y, 0};
  if (timings) {
    timings->derive_s = t1 - t0;  // derivation and turtle together, per plant in parallel
    timings->place_s = now_seconds() - t1;
  }
  return stand;
}

}  // namespace canopy
