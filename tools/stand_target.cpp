// A stand to a target LAI or ground cover: the plant spacing found by bisection.
#include "tools/stand_target.hpp"

#include "geometry/stand_metrics.hpp"
#include "tools/cli_common.hpp"
#include "tools/light_run.hpp"

#include <fmt/format.h>

#include <cmath>
#include <functional>

namespace canopy::cli {
namespace {

constexpr double kMinSpacing = 1e-3, kMaxSpacing = 100;

double tile_area(const RowLayout& l) {
  const std::array<double, 4> t = lattice_tile(l);
  return (t[2] - t[0]) * (t[3] - t[1]);
}

}  // namespace

void add_target_options(CLI::App& app, TargetOptions& t) {
  app.add_option("--target-lai", t.lai,
                 "Choose the plant spacing so the stand's leaf area index (leaflets over the lattice's "
                 "ground) is this")
      ->check(kFinite);
  app.add_option("--target-ground-cover", t.ground_cover,
                 "Choose the plant spacing so the stand's ground cover (periodic, from the zenith) is this")
      ->check(kFinite);
  app.add_option("--target-error", t.error,
                 "Standard error of each ground cover estimate of --target-ground-cover (default 0.002)")
      ->check(kFinite);
}

void place_plants(Stand& stand, const RowLayout& layout) {
  const std::vector<PlantPlacement> at = row_layout(layout);
  if (at.size() != stand.plant_count())
    throw std::invalid_argument("place_plants: the stand is not the layout's rows");
  for (std::size_t p = 0; p < at.size(); ++p) stand.plants[p].x = at[p].x, stand.plants[p].y = at[p].y;
  if (!at.empty()) stand.stand_origin = {at[0].x, at[0].y, 0};
}

SpacingChoice reach_target(Stand& stand, RowLayout& layout, const TargetOptions& t) {
  if (t.lai && t.ground_cover)
    throw std::invalid_argument("--target-lai and --target-ground-cover: give one of them");
  if (t.lai && !(*t.lai > 0 && *t.lai <= 1000))
    throw std::invalid_argument(fmt::format("--target-lai: {} is not in (0, 1000]", *t.lai));
  if (t.ground_cover && !(*t.ground_cover > 0 && *t.ground_cover < 1))
    throw std::invalid_argument(fmt::format("--target-ground-cover: {} is not in (0, 1)", *t.ground_cover));
  if (!(layout.row_spacing > 0))
    throw std::invalid_argument("--target-lai and --target-ground-cover need a row spacing above 0");
  const double target = t.lai ? *t.lai : *t.ground_cover;
  SpacingChoice c;
  PrototypeLibrary lib;
  double leaf = 0;
  for (double a : leaflet_area_per_plant(stand, lib)) leaf += a;
  // The figure at spacing s (falling as s grows) and its standard error.
  double se = 0;
  const std::function<double(double)> figure = [&](double s) -> double {
    ++c.evaluations;
    RowLayout l = layout;
    l.plant_spacing = s;
    if (t.lai) return leaf / tile_area(l);
#ifdef CANOPY_HAVE_LIGHT
    place_plants(stand, l);
    light::LightConfig cfg;
    cfg.sky_directions = 0;
    cfg.error = t.error.value_or(0.002);
    const std::array<double, 4> tile = lattice_tile(l);
    cfg.tile = {tile[0] - stand.stand_origin.x, tile[1] - stand.stand_origin.y,
                tile[2] - stand.stand_origin.x, tile[3] - stand.stand_origin.y};
    const light::LightResult r = light::compute_light(stand, lib, cfg);
    se = r.ground.fraction.se;
    return r.ground.fraction.value;
#else
    throw std::invalid_argument("--target-ground-cover: this build has no ray caster (Embree was not found)");
#endif
  };
  // A bracket [lo, hi] with figure(lo) >= target >= figure(hi), from the layout's spacing.
  double lo = std::clamp(layout.plant_spacing > 0 ? layout.plant_spacing : 0.4, kMinSpacing, kMaxSpacing),
         hi = lo;
  double f = figure(lo);
  if (f >= target) {
    while (f >= target) {
      if (hi >= kMaxSpacing)
        throw std::invalid_argument(
            fmt::format("the target {} is still exceeded at a plant spacing of {} m", target, kMaxSpacing));
      lo = hi, hi = std::min(kMaxSpacing, hi * 2), f = figure(hi);
    }
  } else {
    while (f < target) {
      if (lo <= kMinSpacing)
        throw std::invalid_argument(
            fmt::format("the target {} cannot be reached at this row spacing and age: at a plant spacing of "
                        "{} m it is {:.4f}",
                        target, kMinSpacing, f));
      hi = lo, lo = std::max(kMinSpacing, lo / 2), f = figure(lo);
    }
  }
  // Bisection: to a micrometre for LAI (exact), for ground cover until the spacings are a
  // millimetre apart or the estimate is within its standard error of the target.
  double mid = 0.5 * (lo + hi), at = figure(mid);
  while (hi - lo > (t.lai ? 1e-9 * hi : 1e-3) && !(t.ground_cover && std::abs(at - target) <= se)) {
    if (at >= target) lo = mid;
    else hi = mid;
    mid = 0.5 * (lo + hi), at = figure(mid);
  }
  layout.plant_spacing = mid;
  place_plants(stand, layout);
  c.plant_spacing = mid, c.reached = at, c.standard_error = t.lai ? 0.0 : se;
  return c;
}

nlohmann::ordered_json target_json(const TargetOptions& t, const SpacingChoice& c) {
  nlohmann::ordered_json j;
  j["figure"] = t.lai ? "lai" : "ground_cover";
  j["target"] = t.lai ? *t.lai : *t.ground_cover;
  j["plant_spacing"] = c.plant_spacing;
  j["reached"] = c.reached;
  j["standard_error"] = c.standard_error;
  j["evaluations"] = c.evaluations;
  return j;
}

}  // namespace canopy::cli
