// The build's 8-at-a-time OBB fit (collision/lanes/obb_fit_lanes.hpp) against make_obb, the one
// definition both backends share: the same OBB bit for bit on random transforms (rotated,
// scaled unevenly, far from the origin), degenerate boxes, zero and undefined columns (make_obb's
// completion of the frame) and groups of 1 to 8 organs.
#include "collision/lanes/obb_fit_lanes.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

using namespace canopy;

namespace {

/// A random transform: a rotation (from a random unit quaternion) times a scale per axis, moved
/// up to `far` from the origin; now and then a column scaled to zero, tiny or huge, or NaN.
Affine3f random_transform(std::mt19937& g, float far) {
  std::normal_distribution<float> n(0, 1);
  std::uniform_real_distribution<float> u(-1, 1), s(0.001f, 2.0f);
  float q[4] = {n(g), n(g), n(g), n(g)};
  const float l = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (float& v : q) v /= l;
  const float w = q[0], x = q[1], y = q[2], z = q[3];
  Vec3f col[3] = {{1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)},
                  {2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)},
                  {2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)}};
  for (Vec3f& c : col) {
    const int pick = static_cast<int>(g() % 40);
    c = c * (pick == 0 ? 0.0f : pick == 1 ? 1e-20f : pick == 2 ? 1e15f : s(g));
    if (pick == 3) c.y = std::numeric_limits<float>::quiet_NaN();
  }
  Affine3f t;
  t.c0 = col[0], t.c1 = col[1], t.c2 = col[2];
  t.t = Vec3f{u(g), u(g), u(g)} * far;
  return t;
}

Box3f random_box(std::mt19937& g) {
  std::uniform_real_distribution<float> u(-0.5f, 0.5f), e(0.0f, 0.3f);
  Box3f b;
  b.lo = {u(g), u(g), u(g)};
  b.hi = {b.lo.x + (g() % 8 == 0 ? 0.0f : e(g)), b.lo.y + (g() % 8 == 0 ? 0.0f : e(g)), b.lo.z + e(g)};
  return b;
}

bool same_bits(const Obb& a, const Obb& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

TEST_CASE("eight OBB fits at once give make_obb's OBB bit for bit, degenerate frames included") {
  std::mt19937 g(2024);
  int differ = 0, fitted = 0, completed = 0;
  for (int round = 0; round < 4000; ++round) {
    const int count = 1 + round % 8;
    const float far = round % 3 == 0 ? 5000.0f : round % 3 == 1 ? 1.0f : 0.0f;
    const float inflate = round % 4 == 0 ? 0.01f : 0.0f;
    std::vector<Affine3f> t(8);
    std::vector<Box3f> b(8);
    const Affine3f* tp[8];
    const Box3f* bp[8];
    Obb got[8], sentinel;
    std::memset(static_cast<void*>(&sentinel), 0x5a, sizeof sentinel);
    Obb* out[8];
    for (int k = 0; k < 8; ++k) {
      t[k] = random_transform(g, far), b[k] = random_box(g);
      tp[k] = &t[k], bp[k] = &b[k], got[k] = sentinel, out[k] = &got[k];
    }
    make_obbs8(tp, bp, count, inflate, out);
    for (int k = 0; k < 8; ++k) {
      if (k >= count) {
        CHECK(same_bits(got[k], sentinel));  // nothing written past the group
        continue;
      }
      const Obb want = make_obb(t[k], b[k], inflate);
      INFO("round " << round << " lane " << k);
      const bool same = same_bits(got[k], want);
      CHECK(same);
      differ += !same, ++fitted;
      bool whole = true;
      for (const Vec3f& c : {t[k].c0, t[k].c1, t[k].c2}) whole = whole && std::sqrt(dot(c, c)) > 0;
      completed += !whole;
    }
  }
  CHECK(differ == 0);
  CHECK(fitted > 15000);
  CHECK(completed > 500);  // zero, underflowing and NaN columns went through make_obb's completion
}
