// Light by rasterization against the ray caster it stands in for: cell by cell on seeded stands
// (the same first hit for every ray but those that graze an edge), against the analytic shadows
// the ray caster is held to, and the same counts on any thread count.
#include "geometry/layout.hpp"
#include "geometry/thread_limit.hpp"
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

Stand tomato_rows(std::uint64_t seed) {
  GrowRequest req;
  req.grammar = canopy::test::source("grammars/tomato.yaml");
  req.steps = 14;
  req.lod = 1;
  RowLayout layout;
  layout.rows = 2, layout.per_row = 3, layout.random_rotation = true, layout.jitter = 0.03;
  layout.seed = seed;
  req.plants = row_layout(layout);
  return grow_stand(req);
}

/// Every cell of a direction's grid: the organ the rasterizer keeps and the one the ray caster
/// hits first. Returns how many disagree; where both hit, the heights must agree closely.
std::size_t disagreements(const Stand& s, PrototypeLibrary& lib, Vec3d to, const light::Box2d& region,
                          bool periodic, double rays, std::size_t& cells, std::size_t& hits) {
  light::Scene scene(s, lib);
  if (periodic) scene.set_period(region.width(), region.height());
  scene.build();
  const light::RasterStand raster(s, lib);
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
    const Stand s = tomato_rows(seed);
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

TEST_CASE("raster: a disk and a slab cast their analytic shadows, across the periodic edge too") {
  const double r = 0.1;
  for (double tilt : {0.0, 40 * kDeg}) {
    const Stand s = one_organ(PrototypeKind::disk, OrganKind::leaflet, 2,
                              disk_at({0.2f, -0.1f, 0.5f}, static_cast<float>(r), tilt));
    const light::Box2d tile{-0.25, -0.25, 0.25, 0.25};
    PrototypeLibrary lib;
    light::LightConfig c = beams(kSuns, tile, false, 0.0005);
    c.caster = light::Caster::raster;
    const light::LightResult res = light::compute_light(s, lib, c);
    CHECK(res.raster_rays == res.rays);
    const Vec3d n{0, std::sin(tilt), std::cos(tilt)};
    for (const light::DirectionLight& d : res.direct) {
      const Vec3d to = light::toward(d.elevation_deg, d.azimuth_deg);
      check_area(d, tile, polygon_area(16, r) * std::abs(dot(n, to)) / to.z);
    }
  }
  for (Vec3f c : {Vec3f{1.0f, 0.5f, 0.4f}, Vec3f{1.0f, 1.0f, 0.4f}, Vec3f{0.5f, 0.5f, 0.9f}}) {
    const Stand s =
        one_organ(PrototypeKind::disk, OrganKind::leaflet, 2, disk_at(c, static_cast<float>(r), 0));
    const light::Box2d tile{0, 0, 1, 1};
    PrototypeLibrary lib;
    light::LightConfig cfg = beams(kSuns, tile, true, 0.0005);
    cfg.caster = light::Caster::raster;
    const light::LightResult res = light::compute_light(s, lib, cfg);
    for (const light::DirectionLight& d : res.direct) check_area(d, tile, polygon_area(16, r));
  }
  const float a = 0.2f, h = 0.01f;
  Affine3f t;
  t.c0 = {a, 0, 0}, t.c1 = {0, a / 2, h}, t.c2 = {0, -a / 2, h}, t.t = {0.1f, 0.3f, 0.7f};
  const Stand slab = one_organ(PrototypeKind::cylinder, OrganKind::leaflet, 1, t);
  const light::Box2d tile{-0.25, -0.25, 0.25, 0.25};
  PrototypeLibrary lib;
  light::LightConfig cfg = beams(kSuns, tile, false, 0.0005);
  cfg.caster = light::Caster::raster;
  const light::LightResult res = light::compute_light(slab, lib, cfg);
  for (const light::DirectionLight& d : res.direct) {
    const Vec3d to = light::toward(d.elevation_deg, d.azimuth_deg);
    const double across = a * a * std::abs(to.z) + a * 2 * h * std::abs(to.x) + a * 2 * h * std::abs(to.y);
    check_area(d, tile, across / to.z);
  }
}

TEST_CASE("raster: the same counts on any thread count, and close to the ray caster's") {
  const Stand s = tomato_rows(1);
  light::LightConfig c = beams({{40, 70}}, {-0.2, -0.5, 1.0, 1.5}, true, 0.004);
  c.sky_directions = 12;
  c.plant_error = 0.004;
  c.caster = light::Caster::raster;
  light::LightResult one, two, traced;
  {
    const ThreadLimit t(1);
    PrototypeLibrary lib;
    one = light::compute_light(s, lib, c);
  }
  {
    const ThreadLimit t(2);
    PrototypeLibrary lib;
    two = light::compute_light(s, lib, c);
    light::LightConfig ct = c;
    ct.caster = light::Caster::trace;
    traced = light::compute_light(s, lib, ct);
  }
  CHECK(one.raster_rays == one.rays);
  CHECK(traced.raster_rays == 0);
  const auto same = [](const light::DirectionLight& x, const light::DirectionLight& y) {
    CHECK(x.rays == y.rays);
    CHECK(x.fraction.value == y.fraction.value);
    CHECK(x.fraction.se == y.fraction.se);
    for (std::size_t p = 0; p < x.plant.size(); ++p) CHECK(x.plant[p].value == y.plant[p].value);
  };
  same(one.ground, two.ground);
  same(one.direct[0], two.direct[0]);
  same(*one.diffuse, *two.diffuse);
  // The same rays traced: the fractions within a part in a thousand of the rays.
  const auto close = [](const light::DirectionLight& x, const light::DirectionLight& y) {
    CHECK(x.rays == y.rays);
    CHECK(std::abs(x.fraction.value - y.fraction.value) <= 1e-3);
  };
  close(one.ground, traced.ground);
  close(one.direct[0], traced.direct[0]);
  close(*one.diffuse, *traced.diffuse);
}
