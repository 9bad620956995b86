// The CPU backend's 8-at-a-time OBB test (collision/lanes/obb_lanes.hpp) against obb_overlap, the
// one definition both backends share: the same answer lane by lane on random boxes, on parallel
// and degenerate ones, with NaN, and on pairs moved to the last float at which they still meet
// (where any change in the order of operations would show).
#include "collision/lanes/obb_lanes.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

using namespace canopy;

namespace {

struct Case {
  Obb a, b;
  Vec3f offset;
};

Vec3f unit(Vec3f v) { return v * (1 / std::sqrt(dot(v, v))); }

/// A random OBB: any orientation, axis-aligned, or one axis tilted by a few ulps off a
/// coordinate axis (near-parallel edge pairs); now and then an extent of zero.
Obb random_obb(std::mt19937& g, int kind) {
  std::uniform_real_distribution<float> u(-1, 1), h(0.0f, 0.4f);
  Vec3f x{1, 0, 0}, y{0, 1, 0};
  if (kind == 1) {
    x = unit({u(g), u(g), u(g)});
    y = unit(cross(x, Vec3f{u(g), u(g), u(g)}));
  } else if (kind == 2) {
    x = unit({1, 1e-7f * u(g), 1e-7f * u(g)});
    y = unit(cross(Vec3f{0, 0, 1}, x));
  }
  Obb o;
  o.centre = Vec3f{u(g), u(g), u(g)} * 0.4f;
  o.axis[0] = x, o.axis[1] = y, o.axis[2] = cross(x, y);
  for (float& e : o.half) e = g() % 7 == 0 ? 0.0f : h(g);
  set_radius(o);
  return o;
}

/// Tests `cases` in batches of 1 to 8 pairs (lanes past the batch's size keep earlier pairs'
/// pointers) and counts the lanes whose answer differs from obb_overlap's.
int differences(const std::vector<Case>& cases, std::mt19937& g, int& overlaps) {
  int differ = 0;
  ObbBatch batch;
  for (std::size_t i = 0; i < cases.size();) {
    const std::size_t n = std::min<std::size_t>(cases.size() - i, 1 + g() % ObbBatch::kLanes);
    batch.size = 0;
    for (std::size_t k = 0; k < n; ++k)
      batch.add(cases[i + k].a, cases[i + k].b, cases[i + k].offset, static_cast<std::int32_t>(k), 0, 0, 0);
    const unsigned got = batch.overlapping();
    CHECK((got >> n) == 0u);  // nothing past the batch
    for (std::size_t k = 0; k < n; ++k) {
      const bool want = obb_overlap(cases[i + k].a, cases[i + k].b, cases[i + k].offset);
      overlaps += want;
      differ += want != (((got >> k) & 1u) != 0);
    }
    i += n;
  }
  return differ;
}

}  // namespace

TEST_CASE("an empty batch of OBB tests reads no OBB and finds nothing") {
  // The pass flushes every thread's batch after its last plant pair, full or not: an empty one
  // must not read the (null or stale) OBB pointers it keeps.
  const ObbBatch empty;
  CHECK(empty.overlapping() == 0u);
}

TEST_CASE("eight OBB tests at once give obb_overlap's answer lane by lane") {
  std::mt19937 g(11);
  std::uniform_real_distribution<float> u(-1, 1);
  std::vector<Case> cases;
  for (int i = 0; i < 30000; ++i) {
    Case c{random_obb(g, i % 3), random_obb(g, (i / 3) % 3), Vec3f{0, 0, 0}};
    if (i % 5 == 0) c.offset = {u(g), u(g), 0};  // another plant's frame
    if (i % 11 == 0)
      c.offset = {1000 + u(g), -2000 + u(g), 0}, c.b.centre = c.b.centre - c.offset;  // far from the origin
    if (i % 97 == 0) c.b.centre.y = std::numeric_limits<float>::quiet_NaN();          // meets nothing
    cases.push_back(c);
  }
  int overlaps = 0;
  CHECK(differences(cases, g, overlaps) == 0);
  CHECK(overlaps > 3000);
  CHECK(overlaps < 27000);
}

TEST_CASE("eight OBB tests at once agree with obb_overlap at the last float where boxes still meet") {
  // b starts on a's centre and moves along a random direction; bisection over the distance
  // finds the last float at which obb_overlap still reports overlap, and the pairs a few floats
  // either side of it are tested: there the answer turns on the last bit of every sum.
  std::mt19937 g(12);
  std::uniform_real_distribution<float> u(-1, 1);
  std::vector<Case> cases;
  for (int i = 0; i < 3000; ++i) {
    const Obb a = random_obb(g, i % 3);
    Obb b = random_obb(g, (i + 1) % 3);
    b.centre = a.centre;
    const Vec3f dir = unit({u(g), u(g), i % 4 == 0 ? 0.0f : u(g)});
    if (!obb_overlap(a, b, Vec3f{0, 0, 0})) continue;  // degenerate boxes that do not even meet at one centre
    float lo = 0, hi = 4;
    while (std::nextafter(lo, hi) < hi) {
      const float mid = lo + (hi - lo) / 2;
      (obb_overlap(a, b, dir * mid) ? lo : hi) = mid;
    }
    float s = lo;
    for (int k = 0; k < 3; ++k) s = std::nextafter(s, 0.0f);
    for (int k = 0; k < 7; ++k, s = std::nextafter(s, hi)) cases.push_back({a, b, dir * s});
  }
  int overlaps = 0;
  CHECK(cases.size() > 15000);
  CHECK(differences(cases, g, overlaps) == 0);
  CHECK(overlaps > static_cast<int>(cases.size()) / 3);  // both answers occur at the edge
  CHECK(overlaps < static_cast<int>(cases.size()) * 2 / 3 + 1);
}
