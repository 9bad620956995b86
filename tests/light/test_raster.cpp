// Light by rasterization against the ray caster it stands in for: cell by cell on seeded stands
// (the same first hit for every ray but those that graze an edge), and the whole computation's
// fractions (the analytic shadows and the thread counts, drawn too, are in test_light.cpp).
#include "geometry/layout.hpp"
#include "light/light.hpp"
#include "light/raster_stand.hpp"
#include "light/sky.hpp"
#include "tests/light/stands.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <vector>

using namespace canopy;
using namespace canopy::test::shadows;
using canopy::test::beams;
using canopy::test::one_organ;

namespace {

/// Every cell of a direction's grid: the organ the rasterizer keeps and the one the ray caster
/// hits first. Returns how many disagree; where both hit, the heights must agree closely.
std::size_t disagreements(const Stand& s, PrototypeLibrary& lib, Vec3d to, const light::Box2d& region,
                          bool periodic, double rays, std::size_t& cells, std::size_t& hits) {
  light::Scene scene(s, lib);
  if (periodic) scene.set_period(region.width(), region.height());
  scene.build();
  const light::OrganIndex organs(s);
  const light::RasterStand raster(s, lib, organs);
  light::DirectionJob job;
  job.toward = to, job.grid = light::make_grid(region, rays), job.seed = 3, job.stream = 9;
  job.periodic = periodic;
  const light::RasterGrid g = light::raster_grid(job);
  std::vector<std::uint64_t> keys(job.grid.rays(), 0);
  light::rasterize(raster.view(), g, keys.data());
  const double top = scene.hi().z + 1e-3, t_max = top / to.z;
  std::size_t differ = 0;
  cells = keys.size(), hits = 0;
  for (std::uint64_t j = 0; j < job.grid.ny; ++j)
    for (std::uint64_t i = 0; i < job.grid.nx; ++i) {
      Vec3d ground;
      light::cell_point(g, i, j, ground.x, ground.y);
      const Vec3d org = ground + to * t_max;
      const light::Hit hit = scene.trace(org, Vec3d{-to.x, -to.y, -to.z}, t_max);
      const std::uint64_t key = keys[j * job.grid.nx + i];
      const std::int64_t organ = light::key_organ(key);
      hits += organ >= 0;
      if (organ != hit.organ) {
        ++differ;
        continue;
      }
      if (organ >= 0) CHECK(std::abs(light::key_height(key) - (top - to.z * hit.t)) < 1e-4);
    }
  return differ;
}

}  // namespace

TEST_CASE("raster: every ray's first hit is the ray caster's, but for rays grazing an edge") {
  for (std::uint64_t seed : {1u, 2u}) {
    const Stand s = canopy::test::tomato_rows(14, 0.03, seed);
    PrototypeLibrary lib;
    const light::Box2d tile{-0.2, -0.5, 1.0, 1.5};
    for (const light::Beam b : std::vector<light::Beam>{{90, 0}, {55, 30}, {20, 250}})
      for (bool periodic : {true, false}) {
        std::size_t cells = 0, hits = 0;
        const std::size_t differ = disagreements(s, lib, light::toward(b.elevation_deg, b.azimuth_deg), tile,
                                                 periodic, 2e5, cells, hits);
        INFO("seed " << seed << ", sun " << b.elevation_deg << "/" << b.azimuth_deg << ", periodic "
                     << periodic << ": " << differ << " of " << cells << " cells differ, " << hits
                     << " hits");
        CHECK(hits > cells / 20);  // the stand is there to be hit
        CHECK(differ * 10000 <= cells);
      }
  }
}

TEST_CASE("raster: the traced fractions, within a part in a thousand") {
  // The same rays (passes are sized from the estimates, so the counts may differ by a little).
  const Stand s = canopy::test::tomato_rows(14, 0.03, 1);
  light::LightConfig c = beams({{40, 70}}, {-0.2, -0.5, 1.0, 1.5}, true, 0.004);
  c.sky_directions = 12;
  c.plant_error = 0.004;
  PrototypeLibrary lib;
  c.caster = light::Caster::raster;
  const light::LightResult drawn = light::compute_light(s, lib, c);
  c.caster = light::Caster::trace;
  const light::LightResult traced = light::compute_light(s, lib, c);
  CHECK(drawn.raster_rays == drawn.rays);
  CHECK(traced.raster_rays == 0);
  const auto close = [](const light::DirectionLight& x, const light::DirectionLight& y) {
    CHECK(std::abs(x.fraction.value - y.fraction.value) <= 1e-3);
    CHECK(std::abs(x.star.value - y.star.value) <= 2e-3);
  };
  close(drawn.ground, traced.ground);
  close(drawn.direct[0], traced.direct[0]);
  close(*drawn.diffuse, *traced.diffuse);
}
