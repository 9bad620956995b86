// Leaf area index against a hand count: a 3 x 3 stand of hand-built plants whose "leaflets" are
// disks of known radius (their meshes are regular polygons, whose area is known exactly).
#include "geometry/stand_metrics.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

using namespace canopy;

namespace {

/// A plant with one internode and `n` leaflet-kind disks of radius r (lod 1: 8 sides).
void add_plant(Stand& s, double x, double y, int n, float r) {
  PlantRecord p;
  p.x = x, p.y = y;
  p.first_organ = static_cast<std::uint32_t>(s.organ_count());
  const auto plant = static_cast<std::int32_t>(s.plant_count());
  OrganRecord stem;
  stem.plant = plant;
  stem.kind = OrganKind::internode;
  stem.prototype = PrototypeKind::cylinder;
  stem.lod = 1;
  Affine3f t;
  t.c0 = {0, 0, 0.5f}, t.c1 = {0, -0.01f, 0}, t.c2 = {0.01f, 0, 0};
  s.organs.push_back(stem), s.transforms.push_back(t), s.params.push_back({0.5f, 0.01f}),
      s.joint_limit_deg.push_back(60);
  for (int k = 0; k < n; ++k) {
    OrganRecord leaf;
    leaf.plant = plant;
    leaf.parent = static_cast<std::int32_t>(p.first_organ);
    leaf.kind = OrganKind::leaflet;
    leaf.prototype = PrototypeKind::disk;
    leaf.lod = 1;
    Affine3f d;
    d.c0 = {r, 0, 0}, d.c1 = {0, r, 0}, d.c2 = {0, 0, r}, d.t = {0, 0, 0.1f * static_cast<float>(k + 1)};
    s.organs.push_back(leaf), s.transforms.push_back(d), s.params.push_back({r, 0}),
        s.joint_limit_deg.push_back(60);
  }
  p.organ_count = static_cast<std::uint32_t>(s.organ_count()) - p.first_organ;
  s.plants.push_back(p);
}

}  // namespace

TEST_CASE("leaf area index equals the hand count on the inner plants") {
  Stand s;
  const double ps = 0.4, rs = 1.0;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) add_plant(s, c * ps, r * rs, r * 3 + c + 1, 0.05f);  // plant i has i+1 disks
  PrototypeLibrary lib;
  const LeafAreaIndex lai = leaf_area_index(s, lib, 3, 3, ps, rs);
  // The one inner plant (row 1, column 1, index 4) has 5 disks; a regular octagon of circumradius
  // r has area 2 sqrt(2) r^2.
  const double octagon = 2 * std::sqrt(2.0) * 0.05 * 0.05;
  CHECK(lai.inner_only);
  CHECK(lai.plants == 1);
  CHECK(lai.leaf_area == doctest::Approx(5 * octagon).epsilon(1e-6));
  CHECK(lai.lai == doctest::Approx(5 * octagon / (ps * rs)).epsilon(1e-6));
  // Too few rows for inner plants: every plant counts (1 + 2 + 3 disks over 3 plants).
  Stand row;
  for (int c = 0; c < 3; ++c) add_plant(row, c * ps, 0, c + 1, 0.05f);
  const LeafAreaIndex all = leaf_area_index(row, lib, 1, 3, ps, rs);
  CHECK_FALSE(all.inner_only);
  CHECK(all.lai == doctest::Approx(6 * octagon / (3 * ps * rs)).epsilon(1e-6));
  CHECK_THROWS_AS(leaf_area_index(row, lib, 2, 3, ps, rs), std::invalid_argument);
}

TEST_CASE("leaf inclination: the area of leaflet blades by the angle of their normal from the vertical") {
  // Three leaflet-kind disks of one radius: horizontal, turned 45 degrees about x, upright.
  Stand s;
  add_plant(s, 0, 0, 0, 0.1f);
  const float c = std::cos(std::numbers::pi_v<float> / 4), r = 0.1f;
  const Affine3f tilts[3] = {{{r, 0, 0}, {0, r, 0}, {0, 0, r}, {0, 0, 0.2f}},
                             {{r, 0, 0}, {0, r * c, r * c}, {0, -r * c, r * c}, {0, 0, 0.4f}},
                             {{r, 0, 0}, {0, 0, r}, {0, -r, 0}, {0, 0, 0.6f}}};
  for (const Affine3f& t : tilts) {
    OrganRecord leaf;
    leaf.parent = 0;
    leaf.kind = OrganKind::leaflet;
    leaf.prototype = PrototypeKind::disk;
    leaf.lod = 1;
    s.organs.push_back(leaf), s.transforms.push_back(t), s.params.push_back({r, 0}),
        s.joint_limit_deg.push_back(60);
  }
  s.plants[0].organ_count = static_cast<std::uint32_t>(s.organ_count());
  PrototypeLibrary lib;
  const LeafInclination li = leaf_inclination(s, lib);
  REQUIRE(li.fraction.size() == 9);
  CHECK(li.fraction[0] == doctest::Approx(1.0 / 3));
  CHECK(li.fraction[4] == doctest::Approx(1.0 / 3));  // 40-50 degrees
  CHECK(li.fraction[8] == doctest::Approx(1.0 / 3));
  CHECK(li.mean_deg == doctest::Approx(45).epsilon(1e-4));
  // The upright disk reaches 0.1 above its centre at 0.6; the stem's top is at 0.5.
  CHECK(plant_heights(s, lib).at(0) == doctest::Approx(0.7).epsilon(1e-6));
  // A plant without leaflets has no inclination: not the 0 of flat blades.
  Stand bare;
  add_plant(bare, 0, 0, 0, 0.1f);
  const LeafInclination none = leaf_inclination(bare, lib);
  CHECK(none.area == 0);
  CHECK(std::isnan(none.mean_deg));
  for (double f : none.fraction) CHECK(std::isnan(f));
}
