// The CPU backend's 8-at-a-time LCD test (collision/lanes/lcd_lanes.hpp) against lcd_overlap, the one
// definition both backends share: the same answer lane by lane on random boxes, parallel and
// empty ones, and on pairs moved to the last float at which they still meet (where any change in
// the order of operations would show); from a group of LCD lanes (collision/lanes/organ_lanes.hpp), as
// the pass reads a plant's roots.
#include "collision/lanes/lcd_lanes.hpp"
#include "collision/lanes/organ_lanes.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <vector>

using namespace canopy;

namespace {

/// A random LCD box (centred form): any angle, or one of a few shared ones (parallel boxes),
/// now and then empty.
LcdCentred random_root(std::mt19937& g) {
  std::uniform_real_distribution<float> u(-1, 1);
  if (g() % 23 == 0) return lcd_centred(Lcd{});
  Lcd l;
  const float ang = g() % 3 == 0 ? 0.5f * static_cast<float>(g() % 4) : 3.14159f * u(g);
  l.ax = std::cos(ang), l.ay = std::sin(ang);
  for (int d = 0; d < 3; ++d) {
    const float c = 0.3f * u(g), e = g() % 9 == 0 ? 0.0f : 0.01f + 0.3f * std::fabs(u(g));
    l.lo[d] = c - e, l.hi[d] = c + e;
  }
  return lcd_centred(l);
}

/// Tests b[k] against a for every k, 8 lanes at a time (the last lanes of a short group repeat
/// an earlier box), and counts the lanes whose answer differs from lcd_overlap's.
int differences(const LcdCentred& a, const std::vector<LcdCentred>& b, Vec3f offset, int& overlaps) {
  int differ = 0;
  for (std::size_t k0 = 0; k0 < b.size(); k0 += 8) {
    const LcdCentred* lanes[8];
    for (std::size_t t = 0; t < 8; ++t) lanes[t] = &b[std::min(k0 + t, b.size() - 1)];
    LcdLanes group;
    group.assign_empty(8);
    for (std::size_t t = 0; t < 8; ++t) group.set(t, *lanes[t]);
    const unsigned got = lcd_overlapping8(a, group.group(0), offset);
    CHECK((got >> 8) == 0u);
    for (std::size_t t = 0; t < 8; ++t) {
      const bool want = lcd_overlap(a, *lanes[t], offset);
      overlaps += want;
      differ += want != (((got >> t) & 1u) != 0);
    }
  }
  return differ;
}

}  // namespace

TEST_CASE("eight LCD tests at once give lcd_overlap's answer lane by lane") {
  std::mt19937 g(17);
  std::uniform_real_distribution<float> u(-1, 1);
  int overlaps = 0, differ = 0, tested = 0;
  for (int i = 0; i < 4000; ++i) {
    const LcdCentred a = random_root(g);
    std::vector<LcdCentred> b(1 + g() % 20);
    for (LcdCentred& r : b) r = random_root(g);
    const Vec3f offset = i % 2 ? Vec3f{0, 0, 0} : Vec3f{0.3f * u(g), 0.3f * u(g), 0.2f * u(g)};
    differ += differences(a, b, offset, overlaps);
    tested += static_cast<int>((b.size() + 7) / 8 * 8);
  }
  CHECK(differ == 0);
  CHECK(overlaps > tested / 10);  // both answers occur
  CHECK(overlaps < tested * 9 / 10);
}

TEST_CASE("eight LCD tests at once agree at the last float where the boxes meet") {
  // Each pair moved apart along a random direction to where lcd_overlap flips (bisection), then
  // tested at the floats on either side: an operation done in another order or fused would
  // flip some of these.
  std::mt19937 g(19);
  std::uniform_real_distribution<float> u(-1, 1);
  int overlaps = 0, differ = 0, n = 0;
  for (int i = 0; i < 3000; ++i) {
    const LcdCentred a = random_root(g);
    LcdCentred b = random_root(g);
    const Vec3f dir{u(g), u(g), i % 3 == 0 ? 0.0f : 0.5f * u(g)};
    if (!lcd_overlap(a, b, {0, 0, 0}) || lcd_overlap(a, b, dir * 8))
      continue;  // the boxes meet at 0, not at 8
    float lo = 0, hi = 8;
    for (int it = 0; it < 80; ++it) {
      const float mid = 0.5f * (lo + hi);
      (lcd_overlap(a, b, dir * mid) ? lo : hi) = mid;
    }
    std::vector<LcdCentred> bs(8, b);
    for (float t : {lo, hi, std::nextafter(lo, 0.0f), std::nextafter(hi, 9.0f)}) {
      differ += differences(a, bs, dir * t, overlaps);
      n += 8;
    }
  }
  CHECK(differ == 0);
  CHECK(overlaps > n / 4);
  CHECK(overlaps < n * 3 / 4);
}

TEST_CASE("an empty LCD box meets nothing in the 8-at-a-time test either") {
  std::mt19937 g(23);
  const LcdCentred empty = lcd_centred(Lcd{});
  std::vector<LcdCentred> b(8);
  int met = 0;
  for (int i = 0; i < 200; ++i) {
    for (LcdCentred& r : b) r = random_root(g);
    LcdLanes lanes;
    lanes.assign_empty(8);
    for (std::size_t t = 0; t < 8; ++t) lanes.set(t, b[t]);
    CHECK(lcd_overlapping8(empty, lanes.group(0), {0, 0, 0}) == 0u);
    for (std::size_t t = 0; t < 8; ++t) lanes.set(t, empty);
    CHECK(lcd_overlapping8(b[0], lanes.group(0), {0, 0, 0}) == 0u);
    lanes.set(0, b[0]);
    met += lcd_overlapping8(b[0], lanes.group(0), {0, 0, 0}) & 1u;  // a box meets itself unless empty
    LcdLanes unset;  // lanes no box was set in (a plant's run padded to whole groups)
    unset.assign_empty(8);
    CHECK(lcd_overlapping8(b[0], unset.group(0), {0, 0, 0}) == 0u);
  }
  CHECK(met > 150);
}
