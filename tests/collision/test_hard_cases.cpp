// docs/design.md's hard cases, each with its answer worked out by hand.
#include "hard_cases.hpp"
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

bool touch(const Stand& s, std::int32_t a, std::int32_t b) {
  PrototypeLibrary lib;
  ExactScratch x;
  return organs_touch(s, lib, a, b, 0, x);
}

}  // namespace

TEST_CASE("triangle pairs: coplanar, edge on edge and vertex on face (closed sets), zero-area and slivers") {
  for (const TrianglePairCase& c : hard_triangle_pairs()) {
    INFO(c.what);
    CHECK(meet(c.a, c.b) == c.meet);
  }
}

TEST_CASE(
    "hand-built stands: containment in solids, zero-thickness and zero-length organs, leaflets 100x smaller "
    "and larger") {
  for (const BuiltCase& c : hard_built_stands()) {
    INFO(c.what);
    for (const auto& [a, b] : c.touching) CHECK(touch(c.built.stand, a, b));
    for (const auto& [a, b] : c.apart) CHECK_FALSE(touch(c.built.stand, a, b));
    // Detection of the whole stand (every kind taking part) lists the touching pairs, not the others.
    DetectRequest req;
    req.collide = parse_collide_kinds("all");
    const std::vector<Contact> found = make_cpu_backend()->detect(c.built.stand, req).pairs;
    const auto listed = [&](std::int32_t a, std::int32_t b) {
      return std::any_of(found.begin(), found.end(), [&](const Contact& k) {
        return k.organ_a == std::min(a, b) && k.organ_b == std::max(a, b);
      });
    };
    for (const auto& [a, b] : c.touching) CHECK(listed(a, b));
    for (const auto& [a, b] : c.apart) CHECK_FALSE(listed(a, b));
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
  for (const Contact& k : c.pairs)
    twins += k.plant_a == 0 && k.plant_b == 1 && static_cast<std::uint32_t>(k.organ_b) == k.organ_a + n;
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
