// The quick rejections of the host exact test never reject a pair the full test accepts: the
// float plane pre-test (TrianglePlane) and the float edge-axis test (apart_on_edges) against the
// plain triangle distance on random pairs at plant scale, including coordinates a couple of
// metres from the plant origin, thin slivers, and clearances around the distance; the filter of
// single triangles against the other organ's OBB (beyond_obb) against the triangle distance to
// every triangle of a posed organ. And the pose cache never answers with a stale pose.
#include "collision/exact.hpp"
#include "collision/mbvt.hpp"
#include "geometry/solid_bound.hpp"
#include "geometry/triangle_distance.hpp"
#include "tests/collision/hard_cases.hpp"
#include "tests/collision/helpers.hpp"
#include "tests/geometry/reference_distance.hpp"

#include <doctest/doctest.h>

#include <cstring>
#include <random>

using namespace canopy;

using canopy::test::reference_distance;

TEST_CASE("the float plane pre-test rejects only pairs farther apart than the clearance") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1, 1);
  int rejected = 0;
  for (int trial = 0; trial < 30000; ++trial) {
    const Vec3f base{2.0f * u(rng), 2.0f * u(rng), 1.5f + u(rng)};  // up to 2 m from the origin
    const float size = trial % 2 ? 0.02f : 0.002f;                  // leaflet triangles, and small ones
    Vec3f p[3], q[3];
    const Vec3f shift{u(rng) * 2 * size, u(rng) * 2 * size, u(rng) * 2 * size};
    for (int i = 0; i < 3; ++i) {
      p[i] = base + Vec3f{u(rng), u(rng), u(rng)} * size;
      q[i] = base + shift + Vec3f{u(rng), u(rng), u(rng)} * size;
    }
    if (trial % 5 == 0) q[2] = q[0] + (q[1] - q[0]) * 0.5f + Vec3f{0, 0, 1e-7f};  // a sliver
    const double d = reference_distance(p, q);
    for (float c : {0.0f, 1e-4f, static_cast<float>(d)}) {
      const float margin = c + 1e-5f;
      const TrianglePlane pp = TrianglePlane::of(p[0], p[1], p[2]), pq = TrianglePlane::of(q[0], q[1], q[2]);
      const bool reject = pp.beyond(q, margin) || pq.beyond(p, margin) || apart_on_edges(p, q, margin) ||
                          apart_on_edges(q, p, margin);
      if (reject) {
        ++rejected;
        CHECK_MESSAGE(d > c, "trial ", trial, " distance ", d, " clearance ", c);
        const bool touches = c > 0 ? triangles_within(p, q, c) : triangles_intersect(p, q);
        CHECK_FALSE(touches);
      }
    }
  }
  CHECK(rejected > 1000);  // it does reject
}

TEST_CASE("the OBB filter rejects only triangles farther from the organ than the clearance") {
  // Organs of random stands posed in their own plant's frame or a neighbour's; triangles of leaflet
  // size near one of the organ's vertices (touching it, crossing it, or a few mm off), each
  // against every triangle of the posed organ when the filter rejects it.
  std::mt19937 rng(19);
  std::uniform_real_distribution<float> u(-1, 1);
  PrototypeLibrary lib;
  int rejected = 0, kept = 0;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const Stand s = test::random_stand(seed, 6);
    const auto n = static_cast<std::uint32_t>(s.organ_count());
    for (int trial = 0; trial < 1500; ++trial) {
      const auto id = static_cast<std::int32_t>(rng() % n);
      const OrganRecord& r = s.organs[static_cast<std::size_t>(id)];
      const std::int32_t frame = rng() % 2 ? r.plant : static_cast<std::int32_t>(rng() % s.plant_count());
      const PrototypeMesh& mesh = lib.get(r);
      PosedOrgan posed;
      posed.pose(s, mesh, id, s.transforms[static_cast<std::size_t>(id)], r.plant, frame);
      if (posed.vertices().empty()) continue;
      const Vec3f at = posed.vertices()[rng() % posed.vertices().size()];
      const float size = trial % 3 ? 0.02f : 0.002f;
      const float off = trial % 4 == 0 ? 0.0f : 0.01f * static_cast<float>(rng() % 4);
      const Vec3f dir{u(rng), u(rng), u(rng)};
      Vec3f t[3];
      for (int k = 0; k < 3; ++k) t[k] = at + dir * off + Vec3f{u(rng), u(rng), u(rng)} * size;
      if (trial % 7 == 0) t[2] = t[0] + (t[1] - t[0]) * 0.5f;  // a degenerate triangle
      double d = 1e300;
      for (std::size_t i = 0; i < mesh.triangle_count(); ++i) {
        const Vec3f q[3] = {posed.vertices()[mesh.indices[3 * i]], posed.vertices()[mesh.indices[3 * i + 1]],
                            posed.vertices()[mesh.indices[3 * i + 2]]};
        d = std::min(d, reference_distance(t, q));
      }
      for (float c : {0.0f, 1e-4f, static_cast<float>(d)}) {
        if (!beyond_obb(t, posed.obb, c + kRejectSlack)) {
          ++kept;
          continue;
        }
        ++rejected;
        CHECK_MESSAGE(d > c, "seed ", seed, " trial ", trial, " distance ", d, " clearance ", c);
        for (std::size_t i = 0; i < mesh.triangle_count(); ++i) {
          const Vec3f q[3] = {posed.vertices()[mesh.indices[3 * i]],
                              posed.vertices()[mesh.indices[3 * i + 1]],
                              posed.vertices()[mesh.indices[3 * i + 2]]};
          const bool touches = c > 0 ? triangles_within(t, q, c) : triangles_intersect(t, q);
          CHECK_FALSE(touches);
        }
      }
    }
  }
  CHECK(rejected > 1000);  // it does reject
  CHECK(kept > 1000);      // and keeps the near ones
}

TEST_CASE("the float edge-axis test rejects pairs the plane test lets through") {
  // Two crossing-plane triangles side by side: separated along an edge-cross-edge axis only.
  const Vec3f p[3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const Vec3f q[3] = {{0.6f, 0.6f, -1}, {0.6f, 0.6f, 1}, {2, 2, 0}};
  const float margin = 1e-4f + 1e-5f;
  CHECK_FALSE(TrianglePlane::of(p[0], p[1], p[2]).beyond(q, margin));
  CHECK_FALSE(TrianglePlane::of(q[0], q[1], q[2]).beyond(p, margin));
  CHECK(apart_on_edges(p, q, margin));
  CHECK(reference_distance(p, q) > 0.1);
  // Touching ones are never rejected.
  const Vec3f r[3] = {{0.4f, 0.4f, -1}, {0.4f, 0.4f, 1}, {2, 2, 0}};
  CHECK_FALSE(apart_on_edges(p, r, margin));
  CHECK(triangles_intersect(p, r));
}

TEST_CASE("a long-lived exact scratch answers as a fresh one for poses that change") {
  // One scratch (and its pose cache) over many organ pairs at many poses, some repeated, some
  // differing in one transform bit; each answer against a fresh scratch's. Both cache sizes: the
  // turn search's, and detection's two poses, where nearly every pose evicts one.
  const Stand s = test::random_stand(11, 6);
  PrototypeLibrary lib;
  std::mt19937 rng(3);
  ExactScratch kept, kept_small(PoseCache::kDetectionSets);
  Witness witness, witness_small;
  const auto n = static_cast<std::int32_t>(s.organ_count());
  int touching = 0, apart = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const std::int32_t a = static_cast<std::int32_t>(rng() % static_cast<unsigned>(n - 1));
    const std::int32_t b =
        a + 1 + static_cast<std::int32_t>(rng() % static_cast<unsigned>(std::min(n - a - 1, 40)));
    Affine3f ta = s.transforms[static_cast<std::size_t>(a)], tb = s.transforms[static_cast<std::size_t>(b)];
    // Move b onto a (so some pairs touch), then nudge it: by a few mm, or by one float step.
    const Vec3f to_a = ta.t - tb.t;
    const float f = static_cast<float>(rng() % 5) / 4.0f;
    tb.t = tb.t + to_a * f;
    if (rng() % 3 == 0) tb.t.x = std::nextafter(tb.t.x, 1e9f);
    else if (rng() % 2 == 0) tb.t.z += 0.003f;
    ExactScratch fresh;
    const float c = rng() % 2 ? 0.0f : 1e-4f;
    const bool want = organs_touch_at(s, lib, a, ta, b, tb, c, fresh);
    CHECK_MESSAGE(organs_touch_at(s, lib, a, ta, b, tb, c, kept, &witness) == want, "trial ", trial);
    CHECK_MESSAGE(organs_touch_at(s, lib, a, ta, b, tb, c, kept_small, &witness_small) == want, "trial ",
                  trial);
    (want ? touching : apart) += 1;
  }
  CHECK(touching > 100);
  CHECK(apart > 100);
}

TEST_CASE("two solids rejected by their capsules never touch: against the full test and brute force") {
  // Random capped cylinders and spheres (some with unequal radial scales) placed about touching
  // one another, in one plant or in two plants 10^6 m from the origin; clearances 0, 0.1 mm and
  // 1 mm. Where solids_apart rejects a pair, the full test of the posed organs (which does not
  // use it) and the brute-force oracle (every triangle pair, and containment) find no touch;
  // organs_touch, which does use it, answers as the full test every time.
  std::mt19937_64 g(23);
  std::uniform_real_distribution<double> u01(0, 1);
  const auto unit = [&] {
    std::normal_distribution<float> n(0, 1);
    const Vec3f v{n(g), n(g), n(g)};
    return v * (1 / length(v));
  };
  PrototypeLibrary lib;
  int rejected = 0, touching = 0, kept_apart = 0;
  for (int trial = 0; trial < 1500; ++trial) {
    test::Built b;
    const bool two_plants = trial % 2 == 1;
    b.stand.plants[0].x = 1e6, b.stand.plants[0].y = 2e5;
    if (two_plants) {
      b.stand.plants.push_back(b.stand.plants[0]);
      b.stand.plants[1].x += 0.3, b.stand.plants[1].y -= 0.1;
    }
    b.stand.stand_origin = {1e6, 2e5, 0};
    const auto solid = [&](int which, Vec3f at, Vec3f heading) {
      const PrototypeKind kind = (trial >> which) % 3 == 0 ? PrototypeKind::sphere : PrototypeKind::cylinder;
      const float len = static_cast<float>(0.01 + 0.2 * u01(g)),
                  r = static_cast<float>(0.001 + 0.015 * u01(g));
      Vec3f l = cross(heading, unit());
      l = l * (1 / length(l));
      Affine3f m = test::frame(heading, l, at, kind == PrototypeKind::sphere ? r : len, r);
      if (trial % 5 == 0) m.c2 = m.c2 * 0.6f;  // unequal radial scales
      const auto id = b.add(kind, kind == PrototypeKind::sphere ? OrganKind::fruit : OrganKind::internode, m,
                            kind == PrototypeKind::sphere ? r : len, r);
      return std::make_pair(id, r);
    };
    const Vec3f h0 = unit();
    const auto [a, ra] = solid(0, {static_cast<float>(u01(g)), static_cast<float>(u01(g)), 1.0f}, h0);
    // The second starts beside a point of the first's axis, its surface near the first's.
    const Affine3f ta = b.stand.transforms[0];
    const Vec3f beside = ta.t + ta.c0 * static_cast<float>(u01(g) * 1.2 - 0.1) +
                         unit() * (ra * static_cast<float>(0.5 + 2.5 * u01(g)));
    const std::int32_t bo = solid(1, beside, unit()).first;
    if (two_plants) {
      b.stand.organs[1].plant = 1;
      b.stand.plants[0].organ_count = 1;
      b.stand.plants[1].first_organ = 1, b.stand.plants[1].organ_count = 1;
      // Carried into plant 1's frame: the same place in the field.
      b.stand.transforms[1].t = b.stand.transforms[1].t - plant_offset(b.stand, 0, 1);
    }
    const Stand& s = b.stand;
    const Vec3f db = two_plants ? plant_offset(s, 0, 1) : Vec3f{0, 0, 0};
    for (float c : {0.0f, 1e-4f, 1e-3f}) {
      const bool apart =
          solids_apart(s.organs[0].prototype, s.transforms[0], s.organs[1].prototype, s.transforms[1], db, c);
      ExactScratch x;
      const PosedOrgan& pa = x.poses.get(s, lib, a, s.transforms[0], 0);
      const PosedOrgan& pb = x.poses.get(s, lib, bo, s.transforms[1], 0, &pa);
      const bool full = posed_touch(pa, pb, c, x, nullptr);
      ExactScratch y;
      CHECK_MESSAGE(organs_touch(s, lib, a, bo, c, y) == full, "trial ", trial);
      KindMask all{};
      all.fill(true);
      const bool brute = !test::brute_force_exact(s, all, c).empty();
      CHECK_MESSAGE(brute == full, "trial ", trial, " clearance ", c);
      if (apart) {
        ++rejected;
        CHECK_MESSAGE(!full, "trial ", trial, " clearance ", c, ": rejected, yet the organs touch");
      } else if (!full) {
        ++kept_apart;
      }
      touching += full;
    }
  }
  CHECK(rejected > 1000);   // it does reject
  CHECK(touching > 1000);   // the pairs are near enough to touch
  CHECK(kept_apart > 100);  // and the near misses go on to the full test
}

TEST_CASE("the poses take the OBBs of a tree fit with no clearance: the same bits and the same answers") {
  // Detection hands the tree's OBBs to the poses (organs_touch's `obbs`) rather than making
  // them again: that holds only while the tree's OBB of an organ is make_obb(transform, mesh
  // box, 0) bit for bit, which this checks on whole stands, with the answers with and without.
  int pairs = 0, touching = 0;
  for (std::uint64_t seed : {3u, 8u, 21u}) {
    const Stand s = test::random_stand(seed, 6);
    PrototypeLibrary lib;
    const Mbvt m = build_mbvt(s, lib, MbvtConfig{});
    int differ = 0;
    for (std::size_t k = 0; k < s.organ_count(); ++k) {
      if (!m.takes_part[k]) continue;
      const Obb want = make_obb(s.transforms[k], lib.get(s.organs[k]).box, 0);
      differ += std::memcmp(&want, &m.obbs[k], sizeof want) != 0;
    }
    CHECK_MESSAGE(differ == 0, "seed ", seed);
    ExactScratch x, y;
    const auto n = static_cast<std::int32_t>(s.organ_count());
    for (std::int32_t a = 0; a < n; ++a)
      for (std::int32_t b = a + 1; b < n; ++b) {
        if (!m.takes_part[static_cast<std::size_t>(a)] || !m.takes_part[static_cast<std::size_t>(b)])
          continue;
        if (!obb_overlap(m.obbs[static_cast<std::size_t>(a)], m.obbs[static_cast<std::size_t>(b)],
                         plant_offset(s, s.organs[static_cast<std::size_t>(a)].plant,
                                      s.organs[static_cast<std::size_t>(b)].plant)))
          continue;
        const bool with = organs_touch(s, lib, a, b, 0, x, m.obbs.data()),
                   without = organs_touch(s, lib, a, b, 0, y);
        CHECK(with == without);
        ++pairs;
        touching += with;
      }
  }
  CHECK(pairs > 200);
  CHECK(touching > 20);
}
