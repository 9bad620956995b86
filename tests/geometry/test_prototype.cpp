// Prototype meshes: leaflet outline and area, closed solids, outward normals, exact local boxes,
// every vertex a triangle's corner and the corners in lanes.
#include "geometry/organ_mesh.hpp"
#include "geometry/prototype.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

using namespace canopy;

namespace {
double mesh_area(const PrototypeMesh& m) {
  return transformed_area(m, {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 0}});
}

/// Every undirected edge of a closed mesh is used by exactly two triangles, once each way.
bool closed(const PrototypeMesh& m) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  // Caps have their own vertices: compare positions, not indices.
  std::map<std::tuple<float, float, float>, std::uint32_t> weld;
  std::vector<std::uint32_t> id(m.positions.size());
  for (std::size_t i = 0; i < m.positions.size(); ++i)
    id[i] = weld.emplace(std::make_tuple(m.positions[i].x, m.positions[i].y, m.positions[i].z),
                         static_cast<std::uint32_t>(weld.size()))
                .first->second;
  for (std::size_t i = 0; i < m.indices.size(); i += 3)
    for (int k = 0; k < 3; ++k) ++edges[{id[m.indices[i + k]], id[m.indices[i + (k + 1) % 3]]}];
  for (const auto& [e, n] : edges)
    if (n != 1 || !edges.count({e.second, e.first})) return false;
  return true;
}
}  // namespace

TEST_CASE("the leaflet is a real ovate, pointed blade") {
  const PrototypeMesh m = make_prototype(PrototypeKind::leaflet, kDefaultLod);
  CHECK(m.positions.size() >= 16);  // outline points (every vertex is on the outline)
  // Widest below the middle (ovate) and pointed at the tip.
  CHECK(leaflet_half_width(1.0 / 3) == doctest::Approx(0.5));
  CHECK(leaflet_half_width(0.25) > leaflet_half_width(0.75));
  CHECK(leaflet_half_width(0.99) < 0.02);
  // Area of the mesh within 2 % of the analytic outline's, at every level of detail.
  for (int lod = 1; lod <= 4; ++lod) {
    INFO("lod " << lod);
    const double a = mesh_area(make_prototype(PrototypeKind::leaflet, lod));
    CHECK(std::fabs(a / leaflet_outline_area() - 1) < (lod >= kDefaultLod ? 0.02 : 0.05));
  }
  CHECK(leaflet_outline_area() == doctest::Approx(0.69282).epsilon(1e-4));
  // Flat, with UVs and +Z normals; triangles wound counter-clockwise seen from +Z.
  for (std::size_t i = 0; i < m.indices.size(); i += 3) {
    const Vec3f a = m.positions[m.indices[i]], b = m.positions[m.indices[i + 1]],
                c = m.positions[m.indices[i + 2]];
    CHECK(cross(b - a, c - a).z > 0);
  }
  CHECK(m.uvs.size() == m.positions.size());
}

TEST_CASE("cylinders and spheres are closed solids with outward normals") {
  for (PrototypeKind k : {PrototypeKind::cylinder, PrototypeKind::sphere}) {
    for (int lod = 1; lod <= 3; ++lod) {
      const PrototypeMesh m = make_prototype(k, lod);
      INFO(name_of(k) << " lod " << lod);
      CHECK(closed(m));
      const Vec3f centre = k == PrototypeKind::cylinder ? Vec3f{0.5f, 0, 0} : Vec3f{1, 0, 0};
      for (std::size_t i = 0; i < m.indices.size(); i += 3) {
        const Vec3f a = m.positions[m.indices[i]], b = m.positions[m.indices[i + 1]],
                    c = m.positions[m.indices[i + 2]];
        CHECK(dot(cross(b - a, c - a), (a + b + c) * (1.0f / 3) - centre) > 0);
      }
    }
  }
}

TEST_CASE("local boxes are the exact bounds of the vertices") {
  const PrototypeMesh c = make_prototype(PrototypeKind::cylinder, 2);
  CHECK(c.box.lo.x == 0);
  CHECK(c.box.hi.x == 1);
  CHECK(c.box.hi.y == 1);
  const PrototypeMesh s = make_prototype(PrototypeKind::sphere, 2);
  CHECK(s.box.lo.x == 0);
  CHECK(s.box.hi.x == 2);
  const PrototypeMesh l = make_prototype(PrototypeKind::leaflet, 2);
  CHECK(l.box.lo.z == 0);
  CHECK(l.box.hi.z == 0);
  CHECK(l.box.hi.y <= 0.5f);
  CHECK(l.box.hi.y > 0.48f);
}

TEST_CASE("every vertex is a corner of a triangle, and the corners in lanes are the triangles' corners") {
  // The exact stage takes an organ's box from its triangles' corners (collision/exact.cpp), the
  // box of its vertices only while every vertex is a corner.
  for (const PrototypeKind kind :
       {PrototypeKind::cylinder, PrototypeKind::leaflet, PrototypeKind::sphere, PrototypeKind::disk})
    for (int lod = 1; lod <= kMaxLod; ++lod) {
      const PrototypeMesh m = make_prototype(kind, lod);
      std::vector<char> corner(m.positions.size(), 0);
      for (const std::uint32_t i : m.indices) corner[i] = 1;
      INFO("kind " << static_cast<int>(kind) << " lod " << lod);
      CHECK(std::count(corner.begin(), corner.end(), 0) == 0);
      REQUIRE(m.corner_lanes.size() == (m.triangle_count() + 7) / 8 * PrototypeMesh::kCornerGroupFloats);
      for (std::size_t t = 0; t < m.triangle_count(); ++t)
        for (int c = 0; c < 3; ++c) {
          const Vec3f p = m.positions[m.indices[3 * t + static_cast<std::size_t>(c)]];
          const float* lane = &m.corner_lanes[t / 8 * PrototypeMesh::kCornerGroupFloats + t % 8];
          CHECK(lane[8 * (3 * c)] == p.x);
          CHECK(lane[8 * (3 * c + 1)] == p.y);
          CHECK(lane[8 * (3 * c + 2)] == p.z);
        }
    }
}

TEST_CASE("triangle counts per level of detail") {
  CHECK(make_prototype(PrototypeKind::leaflet, 2).triangle_count() == 16);
  CHECK(make_prototype(PrototypeKind::cylinder, 2).triangle_count() == 28);
  CHECK(make_prototype(PrototypeKind::sphere, 2).triangle_count() == 64);
  CHECK(make_prototype(PrototypeKind::disk, 2).triangle_count() == 14);
  CHECK_THROWS_AS(make_prototype(PrototypeKind::disk, 0), std::invalid_argument);
}

TEST_CASE("normals stay perpendicular under non-uniform scale, and degenerate maps stay finite") {
  const Affine3f m{{2, 0, 0}, {0, 0.1f, 0}, {0, 0, 0.1f}, {0, 0, 0}};
  const Vec3f n = transform_normal(m, {0.6f, 0.8f, 0});
  // Tangent (0.8, -0.6, 0) maps to (1.6, -0.06, 0); the normal must be perpendicular to it.
  CHECK(dot(n, Vec3f{1.6f, -0.06f, 0}) == doctest::Approx(0).epsilon(1e-6));
  CHECK(length(n) == doctest::Approx(1));
  const Affine3f flat{{0, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 0}};  // a zero-length organ
  const Vec3f d = transform_normal(flat, {0, 0, 1});
  CHECK(std::isfinite(d.x));
  CHECK(length(d) == doctest::Approx(1));
}

TEST_CASE("make_meshes gives the mesh of every slot the stand uses and no other") {
  Stand s;
  const auto add = [&](PrototypeKind kind, int lod, std::uint8_t shape) {
    OrganRecord o;
    o.prototype = kind, o.lod = static_cast<std::uint8_t>(lod), o.shape = shape;
    s.organs.push_back(o), s.transforms.push_back({{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 0}});
    s.params.push_back({0.1f, 0.01f}), s.joint_limit_deg.push_back(60);
  };
  add(PrototypeKind::cylinder, 2, 0);
  add(PrototypeKind::leaflet, 1, 0);
  add(PrototypeKind::leaflet, 1, 3);
  add(PrototypeKind::cylinder, 2, 0);  // a slot used twice
  PlantRecord p;
  p.organ_count = static_cast<std::uint32_t>(s.organ_count());
  s.plants.push_back(p);
  PrototypeLibrary lib;
  const std::vector<const PrototypeMesh*> meshes = make_meshes(s, lib, 2);
  REQUIRE(meshes.size() == static_cast<std::size_t>(kMeshSlots));
  std::size_t made = 0;
  for (std::size_t slot = 0; slot < meshes.size(); ++slot) made += meshes[slot] != nullptr;
  CHECK(made == 3);
  for (const OrganRecord& r : s.organs) {
    CAPTURE(static_cast<int>(r.prototype));
    CHECK(meshes[static_cast<std::size_t>(mesh_slot(r.prototype, r.lod, r.shape))] == &lib.get(r));
  }
  // A level of detail out of range is the library's to refuse.
  add(PrototypeKind::sphere, kMaxLod + 1, 0);
  CHECK_THROWS(make_meshes(s, lib, 2));
}
