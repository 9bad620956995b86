// Curved leaflets: the shape code, and the curved blade's mesh against the angles it is made from
// (midrib bend, cross-section cup and fold), its area, winding and normals; shape 0 is the flat
// blade as it always was.
#include "geometry/organ_mesh.hpp"
#include "geometry/prototype.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <numbers>

using namespace canopy;

namespace {

constexpr double kDeg = 180 / std::numbers::pi;

double mesh_area(const PrototypeMesh& m, double aspect) {
  return transformed_area(
      m, {{1, 0, 0}, {0, static_cast<float>(aspect), 0}, {0, 0, static_cast<float>(aspect)}, {0, 0, 0}});
}

bool same_mesh(const PrototypeMesh& a, const PrototypeMesh& b) {
  const auto bytes = [](const auto& v) { return v.size() * sizeof(v[0]); };
  return a.positions.size() == b.positions.size() && a.indices == b.indices && a.uvs == b.uvs &&
         std::memcmp(a.positions.data(), b.positions.data(), bytes(a.positions)) == 0 &&
         std::memcmp(a.normals.data(), b.normals.data(), bytes(a.normals)) == 0 &&
         std::memcmp(&a.box, &b.box, sizeof a.box) == 0;
}

/// The curved blade's area at the nominal aspect, by quadrature: lengths across are kept, lengths
/// along are stretched by 1 - bend x (height of the cross-section above the midrib) (the blade
/// stands on the midrib's normal), so dA = a0 (1 - b a0 Z(|y|)) ds dy over the flat outline.
double curved_area(const LeafletShape& shape) {
  const double a0 = kNominalLeafletAspect, b = shape.bend_deg / kDeg, k = shape.cup_deg / kDeg / 0.5,
               f = shape.fold_deg / kDeg;
  const auto Z = [&](double u) {
    return std::fabs(k) > 1e-12 ? (std::cos(f) - std::cos(f + k * u)) / k : u * std::sin(f);
  };
  const int n = 2000;
  double area = 0;
  for (int i = 0; i < n; ++i) {
    const double s = (i + 0.5) / n, w = leaflet_half_width(s);
    for (int j = 0; j < 200; ++j) {
      const double u = (j + 0.5) / 200 * w;
      area += 2 * (1 - b * a0 * Z(u)) * (w / 200) / n;
    }
  }
  return a0 * area;
}

}  // namespace

TEST_CASE("shape codes round-trip, round to their steps and refuse angles out of range") {
  for (int code = 0; code < kShapeCount; ++code) {
    const LeafletShape s = leaflet_shape(static_cast<std::uint8_t>(code));
    const auto back = leaflet_shape_code(s);
    REQUIRE(back);
    CHECK(*back == code);
  }
  CHECK(*leaflet_shape_code({0, 0, 0}) == 0);
  CHECK(leaflet_shape(*leaflet_shape_code({-43, -8, 12})).bend_deg == -40);
  CHECK(leaflet_shape(*leaflet_shape_code({-43, -8, 12})).cup_deg == -15);
  CHECK(leaflet_shape(*leaflet_shape_code({-43, -8, 12})).fold_deg == 10);
  CHECK(leaflet_shape(*leaflet_shape_code({-84.9, -37.4, 34.9})).bend_deg == -80);
  std::string why;
  CHECK_FALSE(leaflet_shape_code({-86, 0, 0}, &why));
  CHECK(why.find("bend must lie in [-80, 70]") != std::string::npos);
  CHECK_FALSE(leaflet_shape_code({0, 23, 0}, &why));
  CHECK(why.find("cup must lie in [-30, 15]") != std::string::npos);
  CHECK_FALSE(leaflet_shape_code({0, 0, -6}, &why));
  CHECK_FALSE(leaflet_shape_code({NAN, 0, 0}));
  CHECK_FALSE(leaflet_shape_code({0, INFINITY, 0}));
}

TEST_CASE("shape 0 is the flat blade, byte for byte, and only leaflets take a shape") {
  for (int lod = 1; lod <= kMaxLod; ++lod)
    CHECK(same_mesh(make_prototype(PrototypeKind::leaflet, lod, 0),
                    make_prototype(PrototypeKind::leaflet, lod)));
  CHECK_THROWS(make_prototype(PrototypeKind::cylinder, 2, 5));
  PrototypeLibrary lib;
  CHECK_THROWS(lib.get(PrototypeKind::sphere, 2, 9));
  CHECK(&lib.get(PrototypeKind::leaflet, 2, 0) != &lib.get(PrototypeKind::leaflet, 2, 9));
  CHECK(&lib.get(PrototypeKind::leaflet, 2, 9) == &lib.get(PrototypeKind::leaflet, 2, 9));
}

TEST_CASE("a curved leaflet is the flat blade carried onto its surface, at every level of detail") {
  for (int code = 1; code < kShapeCount; ++code) {
    const LeafletShape shape = leaflet_shape(static_cast<std::uint8_t>(code));
    for (int lod = 1; lod <= 4; ++lod) {
      INFO("shape " << shape.bend_deg << " " << shape.cup_deg << " " << shape.fold_deg << " lod " << lod);
      const PrototypeMesh m = make_prototype(PrototypeKind::leaflet, lod, static_cast<std::uint8_t>(code));
      const PrototypeMesh flat = make_prototype(PrototypeKind::leaflet, lod);
      REQUIRE(m.uvs.size() == m.positions.size());
      REQUIRE(m.normals.size() == m.positions.size());
      // At the nominal aspect the area is the analytic blade's, within what the chords of a coarse
      // mesh lose (9 % at lod 1, where a cupped blade has one column a side), and near the flat
      // blade's.
      const double a = mesh_area(m, kNominalLeafletAspect), af = mesh_area(flat, kNominalLeafletAspect);
      CHECK(std::fabs(a / curved_area(shape) - 1) < (lod == 1 ? 0.09 : lod == 2 ? 0.03 : 0.02));
      CHECK(std::fabs(a / af - 1) < 0.08);
      // Triangles wound so that each faces the way its corners' normals do.
      for (std::size_t i = 0; i < m.indices.size(); i += 3) {
        const Vec3f p = m.positions[m.indices[i]], q = m.positions[m.indices[i + 1]],
                    r = m.positions[m.indices[i + 2]];
        const Vec3f n = m.normals[m.indices[i]] + m.normals[m.indices[i + 1]] + m.normals[m.indices[i + 2]];
        CHECK(dot(cross(q - p, r - p), n) > 0);
      }
      // The box holds every vertex and is reached on every side.
      for (const Vec3f& v : m.positions) {
        CHECK(v.x >= m.box.lo.x);
        CHECK(v.z <= m.box.hi.z);
      }
      // The midrib (the base and the tip vertices, which lie on it) turns by `bend`: at the
      // nominal aspect the tip lies at (sin b / b, (1 - cos b) / b) of the length.
      const double b = shape.bend_deg / kDeg;
      const Vec3f tip = m.positions[m.positions.size() - 1];
      const double tx = b != 0 ? std::sin(b) / b : 1, tz = b != 0 ? (1 - std::cos(b)) / b : 0;
      CHECK(tip.x == doctest::Approx(tx).epsilon(1e-5));
      CHECK(tip.z * kNominalLeafletAspect == doctest::Approx(tz).epsilon(1e-5));
      CHECK(tip.y == 0);
      CHECK(m.positions[0].x == 0);
      CHECK(m.positions[0].z == 0);
    }
  }
}

TEST_CASE("the cross-section rises by the fold at the midrib and turns by the cup out to the margin") {
  // A blade cupped and folded but straight along its midrib: every row across is the same arc.
  const LeafletShape shape{0, 15, 20};
  const std::uint8_t code = *leaflet_shape_code(shape);
  const int lod = 4;
  const PrototypeMesh m = make_prototype(PrototypeKind::leaflet, lod, code);
  // Rows of 2 lod + 1 vertices from the right margin to the left, after the base vertex.
  const std::size_t row = 2 * lod + 1, mid = 1 + 3 * row + lod;  // the fourth station's midrib vertex
  const Vec3f c = m.positions[mid], next = m.positions[mid + 1], margin = m.positions[mid + lod];
  CHECK(c.y == 0);
  CHECK(c.z == 0);
  // The first step out rises at about the fold plus a little of the cup; the margin's step at
  // about fold + cup x (its half-width / 0.5).
  const double first = std::atan2(next.z - c.z, next.y - c.y) * kDeg;
  CHECK(first > 20);
  CHECK(first < 20 + 15 / static_cast<double>(lod));
  const Vec3f before = m.positions[mid + lod - 1];
  const double last = std::atan2(margin.z - before.z, margin.y - before.y) * kDeg;
  const double w = m.uvs[mid + lod][1] - 0.5;  // the station's half-width (the arc's length across is kept)
  CHECK(last < 20 + 15 * w / 0.5);
  CHECK(last > 20 + 15 * (w - w / lod) / 0.5);
  // Mirror images on the two sides.
  const Vec3f right = m.positions[mid - lod];
  CHECK(right.y == -margin.y);
  CHECK(right.z == margin.z);
}

TEST_CASE("a curved organ's area and normals carried by its transform") {
  // A leaflet 0.1 long and 0.05 wide (the nominal aspect), bent and rolled: its area is the mesh's
  // area at that scale, and its normals are unit and face the way of its triangles.
  Stand s;
  s.organs.push_back(OrganRecord{});
  s.organs[0].prototype = PrototypeKind::leaflet;
  s.organs[0].kind = OrganKind::leaflet;
  s.organs[0].shape = *leaflet_shape_code({-50, -15, 10});
  s.transforms.push_back({{0.1f, 0, 0}, {0, 0.05f, 0}, {0, 0, 0.05f}, {1, 2, 3}});
  s.params.push_back({0.1f, 0.05f});
  PrototypeLibrary lib;
  const double area = organ_area(s, 0, lib);
  CHECK(area == doctest::Approx(0.1 * 0.05 * leaflet_outline_area()).epsilon(0.06));
  OrganMesh om;
  organ_mesh(s, 0, lib, om);
  for (const Vec3f& n : om.normals) CHECK(length(n) == doctest::Approx(1).epsilon(1e-5));
}
