#pragma once
// Stands for the light suites: single hand-placed organs with analytic shadows, and the
// turbid-medium test grammars of grammars/test/.
#include "geometry/layout.hpp"
#include "geometry/stand.hpp"
#include "light/light.hpp"
#include "lsystem/grow.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <numbers>
#include <string>

namespace canopy::test {

inline std::string source(const std::string& relative) {
  if (const char* e = std::getenv("CANOPY_SOURCE_DIR")) return std::string(e) + "/" + relative;
  return std::string(CANOPY_SOURCE_DIR) + "/" + relative;
}

/// A stand of one plant at the origin holding one organ with transform `t`.
inline Stand one_organ(PrototypeKind proto, OrganKind kind, int lod, const Affine3f& t) {
  Stand s;
  OrganRecord r;
  r.plant = 0, r.kind = kind, r.prototype = proto, r.lod = static_cast<std::uint8_t>(lod);
  s.organs.push_back(r), s.transforms.push_back(t), s.params.push_back({1, 1}),
      s.joint_limit_deg.push_back(60);
  PlantRecord p;
  p.organ_count = 1;
  s.plants.push_back(p);
  return s;
}

/// A turbid-medium test canopy (grammars/test/NAME.yaml) of one plant, level of detail 1,
/// constants overridden by `set` ("radius=0.001").
inline Stand turbid(const std::string& name, const std::vector<std::string>& set = {}) {
  GrowRequest req;
  req.grammar = source("grammars/test/" + name + ".yaml");
  for (const auto& s : set) req.load.overrides.push_back(parse_override(s));
  req.lod = 1;
  PlantPlacement p;
  p.seed = 7;
  req.plants.push_back(p);
  return grow_stand(req);
}

/// Two rows of three default tomatoes grown `steps` steps, level of detail 1, turned at random and
/// jittered by up to `jitter` metres (the layout's stream `seed`).
inline Stand tomato_rows(int steps, double jitter, std::uint64_t seed) {
  GrowRequest req;
  req.grammar = source("grammars/tomato.yaml");
  req.steps = steps;
  req.lod = 1;
  RowLayout layout;
  layout.rows = 2, layout.per_row = 3, layout.random_rotation = true, layout.jitter = jitter;
  layout.seed = seed;
  req.plants = row_layout(layout);
  return grow_stand(req);
}

/// A configuration with no sky, periodic or not over `tile`, to standard error `error`, its rays
/// answered as `caster` says.
inline light::LightConfig beams(std::vector<light::Beam> suns, light::Box2d tile, bool periodic, double error,
                                light::Caster caster = light::Caster::automatic) {
  light::LightConfig c;
  c.suns = std::move(suns);
  c.sky_directions = 0;
  c.tile = tile;
  c.periodic = periodic;
  c.error = error;
  c.caster = caster;
  return c;
}

/// Hand-placed organs with analytic shadows and their check.
namespace shadows {

inline constexpr double kDeg = std::numbers::pi / 180;

/// Area of the regular k-gon of circumradius r (the disk prototype's mesh at lod L has 8 L sides).
inline double polygon_area(int k, double r) { return 0.5 * k * r * r * std::sin(2 * std::numbers::pi / k); }

/// A disk of radius r centred at c, its normal tilted by `tilt` from +Z toward +Y.
inline Affine3f disk_at(Vec3f c, float r, double tilt) {
  const float ct = static_cast<float>(std::cos(tilt)), st = static_cast<float>(std::sin(tilt));
  Affine3f t;
  t.c0 = {r, 0, 0}, t.c1 = {0, r * ct, -r * st}, t.c2 = {0, r * st, r * ct}, t.t = c;
  return t;
}

/// The intercepted area (fraction x tile area) agrees with `want` within 4 standard errors, and
/// the standard error is small beside it.
inline void check_area(const light::DirectionLight& d, const light::Box2d& tile, double want) {
  const double got = d.fraction.value * tile.area(), se = d.fraction.se * tile.area();
  INFO("elevation " << d.elevation_deg << ", azimuth " << d.azimuth_deg << ": got " << got << " +- " << se
                    << ", want " << want);
  CHECK(std::abs(got - want) <= 4 * se);
  CHECK(se > 0);
  CHECK(se < 0.03 * want);
}

/// Both ways of answering rays: the analytic shadows hold for each.
inline constexpr light::Caster kCasters[] = {light::Caster::trace, light::Caster::raster};

inline const std::vector<light::Beam> kSuns{{90, 0}, {60, 30}, {35, 250}, {15, 120}};

}  // namespace shadows

}  // namespace canopy::test
