// The clearance test (triangles_within) against a plain reference distance (reference_distance.hpp):
// the quick rejections (plane and edge-axis separations) that the shared predicate tries first
// must never change an answer.
#include "geometry/triangle_distance.hpp"
#include "tests/geometry/reference_distance.hpp"

#include <doctest/doctest.h>

#include <random>

using namespace canopy;

using canopy::test::reference_distance;

TEST_CASE("triangles_within agrees with the plain distance on random pairs near and far") {
  std::mt19937 rng(20261122);
  std::uniform_real_distribution<float> u(-1, 1);
  int near = 0, rejected_on_edges = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const float scale = trial % 3 == 0 ? 0.01f : trial % 3 == 1 ? 0.1f : 1.0f;
    const float spread = trial % 2 ? 0.3f : 1.5f;  // half the pairs overlap often
    Vec3f p[3], q[3];
    const Vec3f shift{u(rng) * spread * scale, u(rng) * spread * scale, u(rng) * spread * scale};
    for (int i = 0; i < 3; ++i) {
      p[i] = Vec3f{u(rng), u(rng), u(rng)} * scale;
      q[i] = Vec3f{u(rng), u(rng), u(rng)} * scale + shift;
    }
    const double d = reference_distance(p, q);
    if (d == 0) {
      CHECK(triangles_within(p, q, 1e-4));
      CHECK(triangles_within(p, q, 1e-4, true));
      continue;
    }
    ++near;
    // Clearly inside and clearly outside the clearance, and on both sides of it closely.
    for (double f : {0.5, 1 - 1e-6, 1 + 1e-6, 2.0}) {
      const double c = d * f;
      CHECK_MESSAGE(triangles_within(p, q, c) == (f > 1), "trial ", trial, " distance ", d, " clearance ", c);
      CHECK(triangles_within(p, q, c, true) == (f > 1));  // the other order of work
    }
    D3 a[3], b[3];
    for (int i = 0; i < 3; ++i) a[i] = d3(p[i]), b[i] = d3(q[i]);
    if (apart_on_edge_axes(a, b, d * 0.5)) ++rejected_on_edges;
    CHECK_FALSE(apart_on_edge_axes(a, b, d * (1 + 1e-6)));  // never a gap wider than the distance
  }
  CHECK(near > 5000);
  CHECK(rejected_on_edges > 100);  // the edge axes do reject (they are not dead code)
}

TEST_CASE("edge over edge: the gap shows on the cross-product axis only") {
  // Two triangles whose closest features are an edge of each, crossing at right angles h apart:
  // neither triangle's plane separates them by h (each plane holds the other's edge direction
  // at a tilt), the edge axis does.
  const float h = 0.002f;
  const Vec3f p[3] = {{-1, 0, 0}, {1, 0, 0}, {0, 0, -1}};     // edge along x at z = 0, hanging down
  const Vec3f q[3] = {{0, -1, h}, {0, 1, h}, {0, 0, 1 + h}};  // edge along y at z = h, standing up
  const double d = reference_distance(p, q);
  CHECK(d == doctest::Approx(h).epsilon(1e-6));
  CHECK(triangles_within(p, q, h * 1.001));
  CHECK_FALSE(triangles_within(p, q, h * 0.999));
  D3 a[3], b[3];
  for (int i = 0; i < 3; ++i) a[i] = d3(p[i]), b[i] = d3(q[i]);
  CHECK(apart_on_edge_axes(a, b, h * 0.999));
  CHECK_FALSE(apart_on_edge_axes(a, b, h * 1.001));
}
