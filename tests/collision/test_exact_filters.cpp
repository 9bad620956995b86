// The quick rejections of the host exact test never reject a pair the full test accepts: the
// float plane pre-test (TrianglePlane) against the plain triangle distance on random pairs at
// plant scale, including coordinates a couple of metres from the plant origin, thin slivers,
// and clearances around the distance.
#include "collision/exact.hpp"
#include "geometry/triangle_test.hpp"
#include "tests/geometry/reference_distance.hpp"

#include <doctest/doctest.h>

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
      const TrianglePlane pp = TrianglePlane::of(p[0], p[1], p[2], margin), pq = TrianglePlane::of(q[0], q[1], q[2], margin);
      const bool reject = pp.beyond(q) || pq.beyond(p);
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
