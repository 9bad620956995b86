// canopy light against analytic answers, its rays traced and drawn: the shadow of a disk and of a
// thin square slab from any sun (isolated and across the periodic tile's edge), and turbid-medium canopies
// whose intercepted fraction and STAR follow from the probability that a random leaf covers a point.
#include "geometry/leaflet_shape.hpp"
#include "geometry/organ_mesh.hpp"
#include "geometry/thread_limit.hpp"
#include "light/light.hpp"
#include "tests/light/stands.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

using namespace canopy;
using canopy::test::beams;
using canopy::test::one_organ;
using canopy::test::turbid;
using namespace canopy::test::shadows;

TEST_CASE("a disk intercepts its area times the cosine of its normal to the sun, over the sun's cosine") {
  const double r = 0.1;
  for (const light::Caster caster : kCasters)
    for (double tilt : {0.0, 40 * kDeg, 90 * kDeg}) {
      const Stand s = one_organ(PrototypeKind::disk, OrganKind::leaflet, 2,
                                disk_at({0.2f, -0.1f, 0.5f}, static_cast<float>(r), tilt));
      const light::Box2d tile{-0.25, -0.25, 0.25, 0.25};
      PrototypeLibrary lib;
      const light::LightResult res = light::compute_light(s, lib, beams(kSuns, tile, false, 0.0005, caster));
      const Vec3d n{0, std::sin(tilt), std::cos(tilt)};
      for (const light::DirectionLight& d : res.direct) {
        const Vec3d to = light::toward(d.elevation_deg, d.azimuth_deg);
        const double want = polygon_area(16, r) * std::abs(dot(n, to)) / to.z;
        if (want < 1e-4) {  // edge-on: nothing to see but a sliver
          CHECK(d.fraction.value * tile.area() < 1e-4);
          continue;
        }
        check_area(d, tile, want);
      }
      // Ground cover: the disk seen from the zenith.
      if (tilt == 0.0) check_area(res.ground, tile, polygon_area(16, r));
    }
}

TEST_CASE("a thin square slab casts the shadow of a box") {
  // A square-section cylinder (level of detail 1) sheared into the box [0, a] x [-a/2, a/2] x [-h, h].
  const float a = 0.2f, h = 0.01f;
  Affine3f t;
  t.c0 = {a, 0, 0}, t.c1 = {0, a / 2, h}, t.c2 = {0, -a / 2, h}, t.t = {0.1f, 0.3f, 0.7f};
  const Stand s = one_organ(PrototypeKind::cylinder, OrganKind::leaflet, 1, t);
  const light::Box2d tile{-0.25, -0.25, 0.25, 0.25};
  PrototypeLibrary lib;
  for (const light::Caster caster : kCasters) {
    const light::LightResult res = light::compute_light(s, lib, beams(kSuns, tile, false, 0.0005, caster));
    for (const light::DirectionLight& d : res.direct) {
      const Vec3d to = light::toward(d.elevation_deg, d.azimuth_deg);
      // A box's area seen along u is the sum of its faces' areas times |cos| over a pair each.
      const double across = a * a * std::abs(to.z) + a * 2 * h * std::abs(to.x) + a * 2 * h * std::abs(to.y);
      check_area(d, tile, across / to.z);
    }
  }
}

TEST_CASE("periodic bounds: a leaf across the tile's edge, or shading tiles away, counts whole") {
  const light::Box2d tile{0, 0, 1, 1};
  const double r = 0.15;
  // Centred on the tile's right edge, on its corner, and inside with a shadow falling far out.
  for (const light::Caster caster : kCasters)
    for (Vec3f c : {Vec3f{1.0f, 0.5f, 0.4f}, Vec3f{1.0f, 1.0f, 0.4f}, Vec3f{0.5f, 0.5f, 0.9f}}) {
      const Stand s =
          one_organ(PrototypeKind::disk, OrganKind::leaflet, 2, disk_at(c, static_cast<float>(r), 0));
      PrototypeLibrary lib;
      const light::LightResult res = light::compute_light(s, lib, beams(kSuns, tile, true, 0.0005, caster));
      for (const light::DirectionLight& d : res.direct) check_area(d, tile, polygon_area(16, r));
      check_area(res.ground, tile, polygon_area(16, r));
    }
}

TEST_CASE("a periodic tile far smaller than the stand is refused, one near its size is not") {
  // A disk 0.3 m across: a 1 mm tile puts 300 x 300 copies of it over each point, a 10 cm tile 3 x 3.
  const Stand s = one_organ(PrototypeKind::disk, OrganKind::leaflet, 2, disk_at({0, 0, 0.4f}, 0.15f, 0));
  PrototypeLibrary lib;
  CHECK_THROWS_WITH_AS(light::compute_light(s, lib, beams({{90, 0}}, {0, 0, 0.001, 0.001}, true, 0.01)),
                       doctest::Contains("--tile: a tile of 0.001 x 0.001 m"), std::invalid_argument);
  CHECK_NOTHROW(light::compute_light(s, lib, beams({{90, 0}}, {0, 0, 0.1, 0.1}, true, 0.01)));
}

TEST_CASE("a periodic tile far larger than the stand: its share sampled, or refused past the ray limit") {
  // A disk 0.3 m across in a 20 m tile (4,400 times its box): the first pass had 4096 rays over the
  // tile, one on the disk; it now puts them on the disk's share, and the area comes out.
  const double r = 0.15;
  const Stand s =
      one_organ(PrototypeKind::disk, OrganKind::leaflet, 2, disk_at({0, 0, 0.4f}, static_cast<float>(r), 0));
  PrototypeLibrary lib;
  const light::Box2d wide{-10, -10, 10, 10};
  const light::LightResult res = light::compute_light(s, lib, beams({{90, 0}}, wide, true, 0.00002));
  check_area(res.direct[0], wide, polygon_area(16, r));
  // 1e9 m: no pass within the limit meets it (every fraction and STAR came out 0 with an error of 0).
  CHECK_THROWS_WITH_AS(light::compute_light(s, lib, beams({{90, 0}}, {0, 0, 1e9, 1e9}, true, 0.01)),
                       doctest::Contains("--tile: a tile of 1e+09 x 1e+09 m over a stand"),
                       std::invalid_argument);
}

TEST_CASE("turbid medium: horizontal leaves intercept 1 - (1 - G a / (A cos theta))^N with G = cos theta") {
  const Stand s = turbid("turbid_horizontal");
  PrototypeLibrary lib;
  const double a = organ_area(s, 0, lib), n = static_cast<double>(s.organ_count());
  const light::LightResult res =
      light::compute_light(s, lib, beams({{90, 20}, {60, 20}, {30, 20}}, {0, 0, 1, 1}, true, 0.002));
  for (const light::DirectionLight& d : res.direct) {
    const double cz = std::sin(d.elevation_deg * kDeg);
    const double want = 1 - std::pow(1 - cz * a / cz, n);
    INFO("zenith " << 90 - d.elevation_deg << ": " << d.fraction.value << " +- " << d.fraction.se
                   << ", formula " << want);
    CHECK(std::abs(d.fraction.value - want) <= 0.01);
    CHECK(d.fraction.se <= 0.002);
  }
}

TEST_CASE("turbid medium: leaves uniform on the sphere intercept 1 - (1 - 0.5 a / (A cos theta))^N") {
  const Stand s = turbid("turbid_spherical");
  PrototypeLibrary lib;
  const double a = organ_area(s, 0, lib), n = static_cast<double>(s.organ_count());
  CHECK(n > 65000);  // a draw rejected at the last step is the only disk missing
  const light::LightResult res =
      light::compute_light(s, lib, beams({{90, 20}, {60, 200}, {30, 20}}, {0, 0, 1, 1}, true, 0.002));
  for (const light::DirectionLight& d : res.direct) {
    const double cz = std::sin(d.elevation_deg * kDeg);
    const double want = 1 - std::pow(1 - 0.5 * a / cz, n);
    INFO("zenith " << 90 - d.elevation_deg << ": " << d.fraction.value << " +- " << d.fraction.se
                   << ", formula " << want);
    CHECK(std::abs(d.fraction.value - want) <= 0.01);
  }
  for (double g : res.leaf_angles.g) CHECK(g == doctest::Approx(0.5).epsilon(0.01));
}

TEST_CASE("turbid medium: a sparse spherical canopy has STAR 0.5") {
  // LAI 0.01: leaves hardly hide one another, so the silhouette is G = 0.5 of the leaf area; the
  // formula gives what little they hide, direction by direction (STAR 0.498). Disks far smaller
  // than the rays' spacing: the rays count like independent ones, 150,000 a direction.
  const Stand s = turbid("turbid_spherical", {"radius=0.00023"});
  PrototypeLibrary lib;
  const double a = organ_area(s, 0, lib), n = static_cast<double>(s.organ_count());
  light::LightConfig c = beams({}, {0, 0, 1, 1}, true, 0.002);
  c.rays_per_m2 = 150000;
  c.sky_directions = 46;
  const light::LightResult res = light::compute_light(s, lib, c);
  REQUIRE(res.diffuse);
  double want = 0;
  for (const light::DirectionLight& d : res.sky_directions) {
    const double cz = std::sin(d.elevation_deg * kDeg);
    want += d.weight * (1 - std::pow(1 - 0.5 * a / cz, n)) * cz / (n * a);
  }
  INFO("STAR " << res.diffuse->star.value << " +- " << res.diffuse->star.se << ", formula " << want);
  CHECK(std::abs(res.diffuse->star.value - 0.5) <= 0.01);
  CHECK(std::abs(res.diffuse->star.value - want) <= 4 * res.diffuse->star.se);
  CHECK(res.diffuse->star.se < 0.0035);
}

TEST_CASE("diffuse light of horizontal leaves: every sky direction sees the same canopy") {
  // For horizontal leaves G / cos theta = 1 at every zenith, so each of the sky's directions
  // (down to 6 degrees above the horizon, crossing many tiles) and their weighted sum intercept
  // 1 - (1 - a / A)^N.
  const Stand s = turbid("turbid_horizontal", {"depth=14", "radius=0.0044"});
  PrototypeLibrary lib;
  const double a = organ_area(s, 0, lib), n = static_cast<double>(s.organ_count());
  light::LightConfig c = beams({}, {0, 0, 1, 1}, true, 0.002);
  c.sky_directions = 46;
  const light::LightResult res = light::compute_light(s, lib, c);
  const double want = 1 - std::pow(1 - a, n);
  REQUIRE(res.diffuse);
  CHECK(std::abs(res.diffuse->fraction.value - want) <= 0.01);
  double weights = 0;
  for (const light::DirectionLight& d : res.sky_directions) {
    weights += d.weight;
    CHECK(std::abs(d.fraction.value - want) <= 0.02 + 4 * d.fraction.se);
  }
  CHECK(weights == doctest::Approx(1.0).epsilon(1e-12));
}

TEST_CASE("the same fractions on any thread count, traced or drawn") {
  const Stand s = canopy::test::tomato_rows(12, 0.02, 1);
  light::LightConfig c = beams({{40, 70}}, {-0.2, -0.5, 1.0, 1.5}, true, 0.004);
  c.sky_directions = 12;
  c.plant_error = 0.004;
  for (const light::Caster caster : {light::Caster::trace, light::Caster::raster}) {
    c.caster = caster;
    light::LightResult one, two;
    {
      const ThreadLimit t(1);
      PrototypeLibrary lib;
      one = light::compute_light(s, lib, c);
    }
    {
      const ThreadLimit t(2);
      PrototypeLibrary lib;
      two = light::compute_light(s, lib, c);
    }
    CHECK(one.raster_rays == (caster == light::Caster::raster ? one.rays : 0));
    const auto same = [](const light::DirectionLight& x, const light::DirectionLight& y) {
      CHECK(x.rays == y.rays);
      CHECK(x.fraction.value == y.fraction.value);
      CHECK(x.fraction.se == y.fraction.se);
      CHECK(x.star.value == y.star.value);
      for (std::size_t l = 0; l < x.layer.size(); ++l) CHECK(x.layer[l].value == y.layer[l].value);
      for (std::size_t p = 0; p < x.plant.size(); ++p) {
        CHECK(x.plant[p].value == y.plant[p].value);
        CHECK(x.plant[p].se == y.plant[p].se);
        CHECK(x.plant_star[p].value == y.plant_star[p].value);
      }
    };
    same(one.ground, two.ground);
    same(one.direct[0], two.direct[0]);
    same(*one.diffuse, *two.diffuse);
    CHECK(one.rays == two.rays);
  }
}

TEST_CASE("a curved leaflet casts the shadow of its own curved mesh, not of the flat blade") {
  // A leaflet whose midrib droops by 80 degrees from base to tip, lying along +X: seen from the
  // zenith its arc covers less ground than the flat blade. The mesh is single-valued over the
  // ground, so its shadow is the sum of its triangles' areas projected on it.
  const float l = 0.2f, w = 0.1f;
  Affine3f t;
  t.c0 = {l, 0, 0}, t.c1 = {0, w, 0}, t.c2 = {0, 0, w}, t.t = {-0.1f, 0, 0.5f};
  Stand s = one_organ(PrototypeKind::leaflet, OrganKind::leaflet, 2, t);
  s.organs[0].shape = *leaflet_shape_code({-80, 0, 0});
  PrototypeLibrary lib;
  const PrototypeMesh &curved = lib.get(s.organs[0]), &flat = lib.get(PrototypeKind::leaflet, 2);
  const auto projected = [&](const PrototypeMesh& m) {
    double area = 0;
    for (std::size_t k = 0; k + 2 < m.indices.size(); k += 3) {
      const Vec3f a = apply(t, m.positions[m.indices[k]]), b = apply(t, m.positions[m.indices[k + 1]]),
                  c = apply(t, m.positions[m.indices[k + 2]]);
      area += 0.5 * std::abs(double(b.x - a.x) * (c.y - a.y) - double(b.y - a.y) * (c.x - a.x));
    }
    return area;
  };
  const double want = projected(curved);
  REQUIRE(want < 0.9 * projected(flat));  // the two are told apart
  const light::Box2d tile{-0.25, -0.25, 0.25, 0.25};
  const light::LightResult res = light::compute_light(s, lib, beams({{90, 0}}, tile, false, 0.0005));
  check_area(res.ground, tile, want);
  check_area(res.direct[0], tile, want);
  // The vertical profile counts the curved blade's own area, not the flat blade's.
  double mesh_area = 0;
  for (std::size_t k = 0; k + 2 < curved.indices.size(); k += 3) {
    const Vec3d a = to_double(apply(t, curved.positions[curved.indices[k]])),
                b = to_double(apply(t, curved.positions[curved.indices[k + 1]])),
                c = to_double(apply(t, curved.positions[curved.indices[k + 2]]));
    mesh_area += 0.5 * length(cross(b - a, c - a));
  }
  double layered = 0;
  for (const double a : res.layer_leaf_area) layered += a;
  CHECK(layered == doctest::Approx(mesh_area).epsilon(1e-6));
}
