#include "tools/sweep_light.hpp"

#include "geometry/clock.hpp"
#include "geometry/leaf_angles.hpp"
#include "tools/light_run.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

namespace canopy::cli {
namespace {

#ifdef CANOPY_HAVE_LIGHT
light::LightConfig sweep_light_config(const SweepOptions& o) {
  LightOptions lo;
  lo.suns = {o.sun};
  lo.sky = o.sky;
  lo.sky_directions = o.sky_directions;
  lo.error = o.light_error;
  light::LightConfig c;
  for (const SunSpec& s : parse_suns(lo)) c.suns.push_back({s.elevation_deg, s.azimuth_deg});
  c.sky = light::parse_sky(o.sky);
  c.sky_directions = o.sky_directions;
  c.error = o.light_error;
  c.tile = {0, 0, 1, 1};
  return c;
}
#endif

}  // namespace

void check_sweep_light(const SweepOptions& o) {
  if (o.no_light) return;
#ifdef CANOPY_HAVE_LIGHT
  if (!(o.light_error >= light::kMinError && o.light_error <= light::kMaxError))
    throw std::invalid_argument(
        fmt::format("--light-error: {} is not in {}..{}", o.light_error, light::kMinError, light::kMaxError));
  light::check_config(sweep_light_config(o));
  if (o.sky_directions < 1)
    throw std::invalid_argument("--sky-directions: a sweep's light needs at least 1 (or --no-light)");
#else
  throw std::invalid_argument("sweep: this build has no ray caster (Embree was not found): give --no-light");
#endif
}

double light_columns(const Stand& stand, const RowLayout& layout, const SweepOptions& o,
                     const std::string& when, RunRow& row) {
#ifdef CANOPY_HAVE_LIGHT
  const auto t0 = std::chrono::steady_clock::now();
  light::LightConfig c = sweep_light_config(o);
  const std::array<double, 4> t = lattice_tile(layout);
  c.tile = {t[0] - stand.stand_origin.x, t[1] - stand.stand_origin.y, t[2] - stand.stand_origin.x,
            t[3] - stand.stand_origin.y};
  PrototypeLibrary lib;
  const light::LightResult r = [&] {
    try {
      return light::compute_light(stand, lib, c);
    } catch (const std::invalid_argument& e) {
      // A sweep has no --tile: its tile is the layout's lattice, so say which spacings made it.
      const std::string what = e.what();
      if (what.rfind("--tile: ", 0) != 0) throw;
      throw std::invalid_argument(fmt::format(
          "the light's tile is the stand's lattice ({:.3g} x {:.3g} m from the plant and row spacings) and is too "
          "small for light: {}; sweep larger spacings, or give --no-light",
          t[2] - t[0], t[3] - t[1], what.substr(8, what.find(": give") - 8)));
    }
  }();
  const double se = std::max({r.ground.fraction.se, r.direct[0].fraction.se, r.diffuse->fraction.se,
                              std::isnan(r.diffuse->star.se) ? 0.0 : r.diffuse->star.se});
  row["ground_cover_" + when] = fmt::format("{:.5f}", r.ground.fraction.value);
  row["direct_" + when] = fmt::format("{:.5f}", r.direct[0].fraction.value);
  row["diffuse_" + when] = fmt::format("{:.5f}", r.diffuse->fraction.value);
  // Undefined without leaflets: an empty cell, which summary.csv leaves out of its means.
  const auto cell = [](double v, int digits) {
    return std::isnan(v) ? std::string() : fmt::format("{:.{}f}", v, digits);
  };
  row["star_" + when] = cell(r.diffuse->star.value, 5);
  row["mean_inclination_" + when] = cell(r.leaf_angles.mean_inclination_deg, 4);
  row["light_se_" + when] = fmt::format("{:.5f}", se);
  return seconds_since(t0);
#else
  (void)stand, (void)layout, (void)o, (void)when, (void)row;
  return 0;
#endif
}

}  // namespace canopy::cli
