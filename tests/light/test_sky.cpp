// The sky's directions and the sun's position against what they must be.
#include "light/sky.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

using namespace canopy;
using namespace canopy::light;

TEST_CASE("sky directions: n of them, weights summing to one, as many per ring as its area holds") {
  for (SkyModel m : {SkyModel::uniform, SkyModel::soc})
    for (int n : {1, 2, 6, 16, 46, 145, 1000}) {
      const std::vector<SkyDirection> d = sky_directions(m, n);
      CHECK(d.size() == static_cast<std::size_t>(n));
      double w = 0;
      for (const SkyDirection& x : d) {
        CHECK(x.elevation_deg > 0);
        CHECK(x.elevation_deg <= 90);
        CHECK(x.weight > 0);
        w += x.weight;
      }
      CHECK(w == doctest::Approx(1).epsilon(1e-12));
      if (n >= 16) {
        // Every cell holds 2 pi / n sr: the weights of a uniform sky are close to cos(zenith)
        // times that over the integral of cos over the hemisphere (pi).
        if (m == SkyModel::uniform)
          for (const SkyDirection& x : d)
            CHECK(
                x.weight ==
                doctest::Approx(std::sin(x.elevation_deg * std::numbers::pi / 180) * 2.0 / n).epsilon(0.25));
      }
    }
  CHECK_THROWS_AS(sky_directions(SkyModel::soc, 0), std::invalid_argument);
  CHECK_THROWS_AS(sky_directions(SkyModel::soc, kMaxSkyDirections + 1), std::invalid_argument);
}

TEST_CASE("the standard overcast sky weighs the zenith more than a uniform sky") {
  const auto u = sky_directions(SkyModel::uniform, 46), s = sky_directions(SkyModel::soc, 46);
  CHECK(s.front().elevation_deg == 90);
  CHECK(s.front().weight > u.front().weight);
  CHECK(s.back().weight < u.back().weight);
  // Exactly: SOC weights of the zenith cap of cos >= c0 are (c^2/2 + 2c^3/3) / (7/6) from c0 to 1.
  const double c0 = 1 - 1.0 / 46;
  CHECK(s.front().weight ==
        doctest::Approx((0.5 + 2.0 / 3 - c0 * c0 / 2 - 2 * c0 * c0 * c0 / 3) / (7.0 / 6)).epsilon(1e-12));
  CHECK(u.front().weight == doctest::Approx((0.5 - c0 * c0 / 2) / 0.5).epsilon(1e-12));
}

TEST_CASE("the sun's position: noon, equinox, solstice, morning and evening") {
  // Day 172 (about the June solstice): declination 23.45 degrees; at noon elevation 90 - lat + 23.45, due
  // south.
  const double decl = 23.45 * std::sin(2 * std::numbers::pi * (284 + 172) / 365.0);
  SunPosition p = solar_position(52, 172, 12);
  CHECK(p.elevation_deg == doctest::Approx(90 - 52 + decl).epsilon(1e-9));
  CHECK(p.azimuth_deg == doctest::Approx(180).epsilon(1e-9));
  // Southern hemisphere: the noon sun is due north.
  p = solar_position(-35, 172, 12);
  CHECK(p.elevation_deg == doctest::Approx(90 - 35 - decl).epsilon(1e-9));
  CHECK(std::abs(std::fmod(p.azimuth_deg + 180, 360) - 180) < 1e-9);
  // Equator at an equinox (day 81: declination about 0): rises due east at 6, sets due west at 18.
  p = solar_position(0, 81, 6);
  CHECK(std::abs(p.elevation_deg) < 0.2);
  CHECK(p.azimuth_deg == doctest::Approx(90).epsilon(0.003));
  p = solar_position(0, 81, 18);
  CHECK(p.azimuth_deg == doctest::Approx(270).epsilon(0.003));
  // Morning and afternoon mirror each other about the meridian.
  const SunPosition am = solar_position(45, 100, 9.5), pm = solar_position(45, 100, 14.5);
  CHECK(am.elevation_deg == doctest::Approx(pm.elevation_deg).epsilon(1e-12));
  CHECK(am.azimuth_deg + pm.azimuth_deg == doctest::Approx(360).epsilon(1e-12));
  CHECK(am.azimuth_deg < 180);
  CHECK_THROWS_AS(solar_position(91, 100, 12), std::invalid_argument);
  CHECK_THROWS_AS(solar_position(45, 0, 12), std::invalid_argument);
  CHECK_THROWS_AS(solar_position(45, 100, 25), std::invalid_argument);
}

TEST_CASE("toward: elevation and compass azimuth to a unit vector, +Y north, +X east") {
  const Vec3d n = toward(0, 0), e = toward(0, 90), up = toward(90, 123);
  CHECK(n.y == doctest::Approx(1));
  CHECK(e.x == doctest::Approx(1));
  CHECK(up.z == doctest::Approx(1));
  CHECK(std::abs(up.x) < 1e-12);
}
