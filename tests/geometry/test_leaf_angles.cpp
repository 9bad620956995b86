// The leaf angle distribution and G-function against hand-placed disks of known inclination.
#include "geometry/leaf_angles.hpp"
#include "geometry/leaflet_shape.hpp"
#include "geometry/organ_mesh.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

using namespace canopy;

namespace {

constexpr double kDeg = std::numbers::pi / 180;

/// One plant of disks of radius r with the given inclinations (degrees), each tilted about X.
Stand disks(const std::vector<double>& inclinations, float r) {
  Stand s;
  PlantRecord p;
  for (double incl : inclinations) {
    OrganRecord o;
    o.kind = OrganKind::leaflet, o.prototype = PrototypeKind::disk, o.lod = 2;
    const float c = static_cast<float>(std::cos(incl * kDeg)), sn = static_cast<float>(std::sin(incl * kDeg));
    Affine3f t;
    t.c0 = {r, 0, 0}, t.c1 = {0, r * c, r * sn}, t.c2 = {0, -r * sn, r * c};
    s.organs.push_back(o), s.transforms.push_back(t), s.params.push_back({r, 0}),
        s.joint_limit_deg.push_back(60);
  }
  // A stem that is no leaflet and must not count.
  OrganRecord stem;
  Affine3f st;
  st.c0 = {0, 0, 1}, st.c1 = {0.01f, 0, 0}, st.c2 = {0, 0.01f, 0};
  s.organs.push_back(stem), s.transforms.push_back(st), s.params.push_back({1, 0.01f}),
      s.joint_limit_deg.push_back(60);
  p.organ_count = static_cast<std::uint32_t>(s.organ_count());
  s.plants.push_back(p);
  return s;
}

}  // namespace

TEST_CASE(
    "mean projection: cos theta cos theta_l until the blade turns away, 2 sin theta / pi for vertical "
    "blades") {
  for (double th : {0.0, 20.0, 45.0, 70.0, 89.0}) {
    CHECK(mean_projection(th * kDeg, 0) == doctest::Approx(std::cos(th * kDeg)));
    CHECK(mean_projection(th * kDeg, 90 * kDeg) ==
          doctest::Approx(2 * std::sin(th * kDeg) / std::numbers::pi));
    if (th + 10 <= 90)
      CHECK(mean_projection(th * kDeg, 10 * kDeg) ==
            doctest::Approx(std::cos(th * kDeg) * std::cos(10 * kDeg)));
  }
  // Numerically: the mean over azimuth of |cos| at a crossing case.
  const double th = 70 * kDeg, tl = 60 * kDeg;
  double sum = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double phi = 2 * std::numbers::pi * (i + 0.5) / n;
    sum += std::abs(std::cos(th) * std::cos(tl) + std::sin(th) * std::sin(tl) * std::cos(phi));
  }
  CHECK(mean_projection(th, tl) == doctest::Approx(sum / n).epsilon(1e-8));
}

TEST_CASE("leaf angles: bins, mean inclination and G of hand-placed disks") {
  const float r = 0.05f;
  const double a = 0.5 * 16 * r * r * std::sin(2 * std::numbers::pi / 16);
  PrototypeLibrary lib;
  const Stand s = disks({0, 0, 47, 90}, r);
  const LeafAngles la = leaf_angles(leaf_angle_sums(s, lib));
  CHECK(la.leaf_area == doctest::Approx(4 * a));
  CHECK(la.fraction[0] == doctest::Approx(0.5));
  CHECK(la.fraction[9] == doctest::Approx(0.25));   // 45-50 degrees
  CHECK(la.fraction[17] == doctest::Approx(0.25));  // 85-90 degrees: a vertical blade
  CHECK(la.mean_inclination_deg == doctest::Approx((47.0 + 90.0) / 4).epsilon(1e-5));
  for (std::size_t k = 0; k < kGZenithsDeg.size(); ++k) {
    const double th = kGZenithsDeg[k] * kDeg;
    const double want =
        (2 * std::cos(th) + mean_projection(th, 47 * kDeg) + 2 * std::sin(th) / std::numbers::pi) / 4;
    CHECK(la.g[k] == doctest::Approx(want).epsilon(1e-5));
  }
  // No leaflet area: the mean, fractions and G are undefined (NaN), not 0 as of flat leaflets.
  const LeafAngles none = leaf_angles(LeafAngleSums{});
  CHECK(none.leaf_area == 0);
  CHECK(std::isnan(none.mean_inclination_deg));
  CHECK(std::isnan(none.fraction[0]));
  CHECK(std::isnan(none.g[0]));
}

TEST_CASE("leaf angles of curved leaflets are their own meshes' (bent, cupped, folded), not a flat blade's") {
  // Leaflets of several shapes, horizontal and tilted, against the area-weighted inclination of
  // their posed triangles (organ_mesh: what the exports write).
  Stand s;
  PlantRecord p;
  const LeafletShape shapes[] = {{0, 0, 0}, {-80, 0, 0}, {40, -30, 0}, {0, 15, 30}, {-50, -15, 20}};
  for (int tilt : {0, 35}) {
    const float c = static_cast<float>(std::cos(tilt * kDeg)), sn = static_cast<float>(std::sin(tilt * kDeg));
    for (const LeafletShape& shape : shapes) {
      OrganRecord o;
      o.kind = OrganKind::leaflet, o.prototype = PrototypeKind::leaflet, o.lod = 2;
      o.shape = *leaflet_shape_code(shape);
      Affine3f t;
      t.c0 = {0.2f * c, 0, 0.2f * sn}, t.c1 = {0, 0.1f, 0}, t.c2 = {-0.1f * sn, 0, 0.1f * c};
      s.organs.push_back(o), s.transforms.push_back(t), s.params.push_back({0.2f, 0.1f}),
          s.joint_limit_deg.push_back(60);
    }
  }
  p.organ_count = static_cast<std::uint32_t>(s.organ_count());
  s.plants.push_back(p);
  PrototypeLibrary lib;
  double area = 0, weighted = 0;
  OrganMesh m;
  for (std::size_t i = 0; i < s.organ_count(); ++i) {
    organ_mesh(s, i, lib, m, true);
    const std::vector<std::uint32_t>& idx = m.prototype->indices;
    for (std::size_t k = 0; k + 2 < idx.size(); k += 3) {
      const Vec3d a = to_double(m.positions[idx[k]]), b = to_double(m.positions[idx[k + 1]]),
                  d = to_double(m.positions[idx[k + 2]]);
      const Vec3d n = cross(b - a, d - a);
      const double len = length(n);
      if (!(len > 0)) continue;
      area += 0.5 * len;
      weighted += 0.5 * len * std::acos(std::min(1.0, std::abs(n.z) / len)) / kDeg;
    }
  }
  const LeafAngles la = leaf_angles(leaf_angle_sums(s, lib));
  CHECK(la.leaf_area == doctest::Approx(area).epsilon(1e-6));
  CHECK(la.mean_inclination_deg == doctest::Approx(weighted / area).epsilon(1e-5));
  CHECK(la.mean_inclination_deg > 20);  // the flat blades alone would say (0 + 35) / 2
}
