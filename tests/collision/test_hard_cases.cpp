// DESIGN.md's hard cases, each with its answer worked out by hand.
#include "helpers.hpp"

#include <algorithm>
#include <array>

using namespace canopy;
using namespace canopy::test;

namespace {

bool meet(std::array<Vec3f, 3> a, std::array<Vec3f, 3> b) {
  // Every permutation of either triangle's vertices and both argument orders give one answer.
  const bool want = triangles_intersect(a.data(), b.data());
  std::array<int, 3> pa{0, 1, 2};
  do {
    std::array<int, 3> pb{0, 1, 2};
    do {
      const Vec3f x[3] = {a[pa[0]], a[pa[1]], a[pa[2]]}, y[3] = {b[pb[0]], b[pb[1]], b[pb[2]]};
      REQUIRE(triangles_intersect(x, y) == want);
      REQUIRE(triangles_intersect(y, x) == want);
    } while (std::next_permutation(pb.begin(), pb.end()));
  } while (std::next_permutation(pa.begin(), pa.end()));
  return want;
}

/// A stand of hand-placed organs: one plant, organs given by prototype, transform, kind.
struct Built {
  Stand stand;
  std::int32_t add(PrototypeKind proto, OrganKind kind, Affine3f m, float p0, float p1 = 0) {
    const auto id = static_cast<std::int32_t>(stand.organs.size());
    OrganRecord r;
    r.plant = 0;
    r.parent = -2 - id;  // every organ its own parent chain: nothing is adjacent
    r.kind = kind;
    r.prototype = proto;
    r.lod = 2;
    stand.organs.push_back(r);
    stand.transforms.push_back(m);
    stand.params.push_back({p0, p1});
    stand.joint_limit_deg.push_back(60);
    stand.plants[0].organ_count++;
    return id;
  }
  Built() {
    stand.plants.resize(1);
    stand.grammars = {"hand"};
  }
};

Affine3f frame(Vec3f h, Vec3f l, Vec3f t, float sx, float sy) {
  const Vec3f u = cross(h, l);
  return {h * sx, l * sy, u * sy, t};
}

bool touch(const Stand& s, std::int32_t a, std::int32_t b) {
  PrototypeLibrary lib;
  ExactScratch x;
  return organs_touch(s, lib, a, b, 0, x);
}

}  // namespace

TEST_CASE("coplanar overlapping triangles (and coplanar apart)") {
  CHECK(meet({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}, {{{0.2f, 0.2f, 0}, {1.2f, 0.2f, 0}, {0.2f, 1.2f, 0}}}));
  CHECK(meet({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}, {{{0.1f, 0.1f, 0}, {0.2f, 0.1f, 0}, {0.1f, 0.2f, 0}}}));  // one inside
  CHECK_FALSE(meet({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}, {{{0.6f, 0.6f, 0}, {1.6f, 0.6f, 0}, {0.6f, 1.6f, 0}}}));
}

TEST_CASE("edge on edge and vertex on face touching count (closed sets)") {
  // Shared edge, the second triangle folded up.
  CHECK(meet({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}, {{{0, 0, 0}, {1, 0, 0}, {0, 0, 1}}}));
  // Crossing edges touching at one point.
  CHECK(meet({{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}}}, {{{1, -1, 0}, {1, -1, 1}, {1, 1, 0}}}));
  // A vertex on the face.
  CHECK(meet({{{0, 0, 0}, {4, 0, 0}, {0, 4, 0}}}, {{{1, 1, 0}, {2, 2, 3}, {1, 2, 3}}}));
  // The same vertex a hair above the face: apart.
  CHECK_FALSE(meet({{{0, 0, 0}, {4, 0, 0}, {0, 4, 0}}}, {{{1, 1, 1e-6f}, {2, 2, 3}, {1, 2, 3}}}));
  // Vertex on vertex.
  CHECK(meet({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}, {{{0, 0, 0}, {-1, 0, 0}, {0, 0, -1}}}));
}

TEST_CASE("zero-area and sliver triangles") {
  // A degenerate triangle (a segment) through a face, beside it, and along an edge.
  CHECK(meet({{{0, 0, -1}, {0.2f, 0.2f, 1}, {0.1f, 0.1f, 0}}}, {{{-1, -1, 0}, {2, -1, 0}, {-1, 2, 0}}}));
  CHECK_FALSE(meet({{{5, 5, -1}, {5, 5, 1}, {5, 5, 0}}}, {{{-1, -1, 0}, {2, -1, 0}, {-1, 2, 0}}}));
  CHECK(meet({{{0, 0, 0}, {1, 0, 0}, {0.5f, 0, 0}}}, {{{0.5f, 0, 0}, {2, 0, 0}, {1.5f, 0, 0}}}));  // collinear overlap
  CHECK_FALSE(meet({{{0, 0, 0}, {1, 0, 0}, {0.5f, 0, 0}}}, {{{1.5f, 0, 0}, {2, 0, 0}, {1.7f, 0, 0}}}));
  CHECK(meet({{{0.3f, 0.3f, 0}, {0.3f, 0.3f, 0}, {0.3f, 0.3f, 0}}}, {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}));  // a point on a face
  // A sliver crossing a triangle.
  CHECK(meet({{{-1, 0.5f, 0}, {2, 0.5f, 0}, {2, 0.5001f, 0.0001f}}}, {{{0, 0, -1}, {1, 0, 1}, {0, 1, 1}}}));
}

TEST_CASE("a leaflet tip wholly inside a fruit or a stem, without crossing its surface") {
  Built b;
  const auto fruit = b.add(PrototypeKind::sphere, OrganKind::fruit, frame({0, 0, 1}, {0, -1, 0}, {0, 0, 0}, 0.02f, 0.02f), 0.02f);
  // Sphere centred at (0, 0, 0.02), radius 0.02: a 5 mm leaflet near the centre.
  const auto leaf = b.add(PrototypeKind::leaflet, OrganKind::leaflet, frame({1, 0, 0}, {0, 1, 0}, {-0.002f, 0, 0.02f}, 0.005f, 0.003f), 0.005f, 0.003f);
  const auto stem = b.add(PrototypeKind::cylinder, OrganKind::internode, frame({0, 0, 1}, {0, -1, 0}, {1, 0, 0}, 0.1f, 0.01f), 0.1f, 0.01f);
  const auto inside_stem = b.add(PrototypeKind::leaflet, OrganKind::leaflet, frame({0, 0, 1}, {0, 1, 0}, {1.002f, 0, 0.05f}, 0.01f, 0.004f), 0.01f, 0.004f);
  const auto outside = b.add(PrototypeKind::leaflet, OrganKind::leaflet, frame({1, 0, 0}, {0, 1, 0}, {0.03f, 0, 0.02f}, 0.005f, 0.003f), 0.005f, 0.003f);
  CHECK(touch(b.stand, fruit, leaf));
  CHECK(touch(b.stand, stem, inside_stem));
  CHECK_FALSE(touch(b.stand, fruit, outside));
  CHECK_FALSE(touch(b.stand, fruit, stem));
}

TEST_CASE("zero-thickness and zero-length organs") {
  Built b;
  const auto blade = b.add(PrototypeKind::leaflet, OrganKind::leaflet, frame({1, 0, 0}, {0, 1, 0}, {0, 0, 0}, 0.1f, 0.05f), 0.1f, 0.05f);
  // A cylinder of zero length standing on the blade, and one of zero radius through it.
  const auto flat = b.add(PrototypeKind::cylinder, OrganKind::petiole, frame({0, 0, 1}, {0, -1, 0}, {0.03f, 0, 0}, 0.0f, 0.004f), 0.0f, 0.004f);
  const auto needle = b.add(PrototypeKind::cylinder, OrganKind::petiole, frame({0, 0, 1}, {0, -1, 0}, {0.03f, 0, -0.01f}, 0.02f, 0.0f), 0.02f, 0.0f);
  const auto away = b.add(PrototypeKind::cylinder, OrganKind::petiole, frame({0, 0, 1}, {0, -1, 0}, {0.3f, 0, -0.01f}, 0.02f, 0.0f), 0.02f, 0.0f);
  CHECK(touch(b.stand, blade, flat));
  CHECK(touch(b.stand, blade, needle));
  CHECK_FALSE(touch(b.stand, blade, away));
}

TEST_CASE("leaflets a hundred times smaller and larger than usual") {
  for (float scale : {0.01f, 1.0f, 100.0f}) {
    Built b;
    const float l = 0.1f * scale, w = 0.05f * scale;
    const auto a = b.add(PrototypeKind::leaflet, OrganKind::leaflet, frame({1, 0, 0}, {0, 1, 0}, {0, 0, 0}, l, w), l, w);
    // Crossing blade (vertical, through the first's middle) and a parallel one just above.
    const auto c = b.add(PrototypeKind::leaflet, OrganKind::leaflet, frame({0, 1, 0}, {0, 0, 1}, {0.3f * l, -0.2f * l, -0.01f * l}, l, w), l, w);
    const auto d = b.add(PrototypeKind::leaflet, OrganKind::leaflet, frame({1, 0, 0}, {0, 1, 0}, {0, 0, 0.001f * l}, l, w), l, w);
    INFO("scale " << scale);
    CHECK(touch(b.stand, a, c));
    CHECK_FALSE(touch(b.stand, a, d));
  }
}

TEST_CASE("identical plants on the same spot, and a stand 10^6 m from the origin") {
  GrowRequest req;
  req.grammar = source("grammars/tomato.yaml");
  req.steps = 12;
  PlantPlacement p;
  p.seed = 3;
  req.plants = {p, p};
  const Stand twin = grow_stand(req);
  auto cpu = make_cpu_backend();
  const Contacts c = cpu->detect(twin, DetectRequest{});
  // Every organ that takes part meets its twin.
  std::size_t twins = 0;
  const std::uint32_t n = twin.plants[0].organ_count;
  for (const Contact& k : c.pairs) twins += k.plant_a == 0 && k.plant_b == 1 && static_cast<std::uint32_t>(k.organ_b) == k.organ_a + n;
  std::size_t taking_part = 0;
  const KindMask kinds = default_collide_kinds();
  for (std::uint32_t i = 0; i < n; ++i) taking_part += kinds[static_cast<std::size_t>(twin.organs[i].kind)];
  CHECK(twins == taking_part);

  // The same small stand at the origin and 10^6 m away: the same contacts.
  for (auto& q : req.plants) q.seed = 4;
  req.plants[1].x = 0.3;
  req.plants[1].rotation_deg = 90;
  const auto near = cpu->detect(grow_stand(req), DetectRequest{}).pairs;
  for (auto& q : req.plants) q.x += 1e6, q.y -= 2e6;
  const auto far = cpu->detect(grow_stand(req), DetectRequest{}).pairs;
  CHECK(near == far);
  CHECK(near.size() > 0);
}

TEST_CASE("OBBs with parallel axes: the vanished cross-product axes do not matter") {
  Obb a, b;
  for (Obb* o : {&a, &b}) {
    o->axis[0] = {1, 0, 0}, o->axis[1] = {0, 1, 0}, o->axis[2] = {0, 0, 1};
    o->half[0] = o->half[1] = o->half[2] = 0.5f;
    set_radius(*o);
  }
  a.centre = {0, 0, 0};
  b.centre = {1.0f, 0, 0};  // faces touching
  CHECK(obb_overlap(a, b, {0, 0, 0}));
  b.centre = {1.01f, 0, 0};
  CHECK_FALSE(obb_overlap(a, b, {0, 0, 0}));
  CHECK(obb_overlap(a, b, {-0.02f, 0, 0}));  // the offset between plants moves b back
}
