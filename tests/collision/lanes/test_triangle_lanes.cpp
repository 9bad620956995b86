// The exact stage's 8-at-a-time filter of single triangles (collision/lanes/triangle_lanes.hpp)
// against the scalar tests it stands for, triangle by triangle: the box test in double
// (posed_touch's, a triangle's float box against the other organ's double box widened by the
// clearance) and beyond_obb. On posed organs of random stands against their neighbours' boxes and
// OBBs, and on boxes placed at, one float beyond and a fraction of a float beyond a triangle's
// box, where the float bounds made from the double box must round the right way. Also the
// corners and boxes a pose keeps in lanes against its vertices.
#include "collision/exact.hpp"
#include "collision/lanes/triangle_lanes.hpp"
#include "tests/collision/helpers.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <random>

using namespace canopy;

namespace {

/// posed_touch's box test as it was written before the lanes: float box t against double box o.
bool meets_in_double(const float* t, const double* o) {
  return !(t[0] > o[3] || t[1] > o[4] || t[2] > o[5] || t[3] < o[0] || t[4] < o[1] || t[5] < o[2]);
}

/// Compares near_lanes with the scalar tests for every triangle of `p` against box `box` and OBB
/// `obb`; returns the triangles found near, counting disagreements in `differ`.
int compare(const PosedOrgan& p, const double* box, const Obb& obb, float margin, int& differ) {
  const PrototypeMesh& m = *p.mesh;
  const std::size_t tris = m.triangle_count();
  const FloatBounds bounds(box);
  // The organ's box is its vertices' (in double, as the exact test widens it).
  double vbox[6] = {1e300, 1e300, 1e300, -1e300, -1e300, -1e300};
  for (const Vec3f& v : p.vertices()) {
    const double xyz[3] = {v.x, v.y, v.z};
    for (int k = 0; k < 3; ++k)
      vbox[k] = std::min(vbox[k], xyz[k]), vbox[k + 3] = std::max(vbox[k + 3], xyz[k]);
  }
  for (int k = 0; k < 6; ++k) CHECK(p.box[k] == vbox[k]);
  int near = 0;
  for (std::size_t i = 0; i < tris; ++i) {
    const Vec3f t[3] = {p.vertices()[m.indices[3 * i]], p.vertices()[m.indices[3 * i + 1]],
                        p.vertices()[m.indices[3 * i + 2]]};
    const float tb[6] = {min_f(t[0].x, min_f(t[1].x, t[2].x)), min_f(t[0].y, min_f(t[1].y, t[2].y)),
                         min_f(t[0].z, min_f(t[1].z, t[2].z)), max_f(t[0].x, max_f(t[1].x, t[2].x)),
                         max_f(t[0].y, max_f(t[1].y, t[2].y)), max_f(t[0].z, max_f(t[1].z, t[2].z))};
    for (int k = 0; k < 6; ++k) CHECK(p.tri_box(i, k) == tb[k]);
    // The corners in lanes are the vertices bit for bit (made 8 at a time, not gathered).
    for (int c = 0; c < 3; ++c) {
      const float xyz[3] = {t[c].x, t[c].y, t[c].z};
      for (int k = 0; k < 3; ++k)
        CHECK(std::memcmp(&p.tri_lanes[i / 8 * PosedOrgan::kGroupFloats +
                                       static_cast<std::size_t>(3 * c + k) * 8 + i % 8],
                          &xyz[k], sizeof(float)) == 0);
    }
    const bool want = meets_in_double(tb, box) && !beyond_obb(t, obb, margin);
    const unsigned bits = near_lanes(&p.tri_lanes[i / 8 * PosedOrgan::kGroupFloats], bounds, obb, margin);
    const bool got = (bits >> (i % 8)) & 1u;
    differ += got != want;
    near += want;
  }
  return near;
}

}  // namespace

TEST_CASE("triangles near another organ, 8 at a time, are those the scalar box and OBB tests keep") {
  std::mt19937 rng(23);
  PrototypeLibrary lib;
  int differ = 0, near = 0, far = 0;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const Stand s = test::random_stand(seed, 8);
    const auto n = static_cast<std::uint32_t>(s.organ_count());
    for (int trial = 0; trial < 1500; ++trial) {
      const auto a = static_cast<std::int32_t>(rng() % n);
      // The other organ: one with an id close by (often touching or crossing) or any.
      const auto b = static_cast<std::int32_t>(
          trial % 2 ? (static_cast<std::uint32_t>(a) + 1 + rng() % 12) % n : rng() % n);
      const OrganRecord& ra = s.organs[static_cast<std::size_t>(a)];
      const OrganRecord& rb = s.organs[static_cast<std::size_t>(b)];
      PosedOrgan pa, pb;
      pa.pose(s, lib.get(ra), a, s.transforms[static_cast<std::size_t>(a)], ra.plant, ra.plant);
      pb.pose(s, lib.get(rb), b, s.transforms[static_cast<std::size_t>(b)], rb.plant, ra.plant);
      // Both sides, as posed_touch filters them: a's triangles against b's box and OBB, and b's
      // (posed in a's plant's frame, moved by the origin difference) against a's.
      for (const double c : {0.0, 1e-4, 0.013}) {
        double box_a[6], box_b[6];
        for (int k = 0; k < 3; ++k) {
          box_a[k] = pa.box[k] - c, box_a[k + 3] = pa.box[k + 3] + c;
          box_b[k] = pb.box[k] - c, box_b[k + 3] = pb.box[k + 3] + c;
        }
        const float margin = static_cast<float>(c) + kRejectSlack;
        const int found =
            compare(pa, box_b, pb.obb, margin, differ) + compare(pb, box_a, pa.obb, margin, differ);
        near += found;
        far += static_cast<int>(pa.mesh->triangle_count() + pb.mesh->triangle_count()) - found;
      }
    }
  }
  CHECK(differ == 0);
  CHECK(near > 10000);
  CHECK(far > 10000);
}

TEST_CASE("a box at a triangle's box, a float beyond it or a fraction of a float beyond it") {
  // Every face of the other box placed on a face of a triangle's box: exactly (the boxes touch),
  // one float outside (they miss), and a double between two floats (inside or outside by less
  // than a float: the float bounds must round outwards of the double only as far as the floats
  // compare the same). The OBB is far larger than everything, so only the box test decides.
  std::mt19937 rng(5);
  PrototypeLibrary lib;
  const Stand s = test::random_stand(2, 3);
  Obb huge{};
  huge.axis[0] = {1, 0, 0}, huge.axis[1] = {0, 1, 0}, huge.axis[2] = {0, 0, 1};
  huge.half[0] = huge.half[1] = huge.half[2] = 1e4f;
  set_radius(huge);
  int differ = 0, near = 0, checked = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const auto a = static_cast<std::int32_t>(rng() % s.organ_count());
    const OrganRecord& ra = s.organs[static_cast<std::size_t>(a)];
    PosedOrgan pa;
    pa.pose(s, lib.get(ra), a, s.transforms[static_cast<std::size_t>(a)], ra.plant, ra.plant);
    const std::size_t i = rng() % pa.mesh->triangle_count();
    const int face = static_cast<int>(rng() % 6), axis = face % 3;
    const bool upper = face >= 3;  // the other box's hi on the triangle's lo, or its lo on the triangle's hi
    const float at = pa.tri_box(i, upper ? axis : axis + 3);
    double box[6] = {-1e3, -1e3, -1e3, 1e3, 1e3, 1e3};
    const float outward =
        upper ? -std::numeric_limits<float>::infinity() : std::numeric_limits<float>::infinity();
    const double one_float = std::fabs(static_cast<double>(std::nextafter(at, outward)) - at);
    for (const double place :
         {static_cast<double>(at), static_cast<double>(std::nextafter(at, outward)),
          at + (upper ? -0.5 : 0.5) * one_float, at + (upper ? 0.25 : -0.25) * one_float}) {
      box[upper ? axis + 3 : axis] = place;
      near += compare(pa, box, huge, kRejectSlack, differ);
      ++checked;
    }
  }
  CHECK(differ == 0);
  CHECK(checked == 1600);
  CHECK(near > 400);
}

namespace {

/// Puts triangle u in lane `lane` of a group laid out as PosedOrgan::tri_lanes.
void put(float* group, int lane, const Vec3f* u) {
  for (int c = 0; c < 3; ++c) {
    const float xyz[3] = {u[c].x, u[c].y, u[c].z};
    for (int k = 0; k < 3; ++k) group[8 * (3 * c + k) + lane] = xyz[k];
  }
}

/// Lanes whose answer differs from triangles_rejected's: t against the 8 triangles u[0..7], all
/// lanes asked for and then each of the masks in `wanted` (their lanes only).
int rejected_differences(const Vec3f* t, const Vec3f (*u)[3], float margin, int& rejected,
                         std::initializer_list<unsigned> wanted = {}) {
  float group[PosedOrgan::kGroupFloats] = {};
  for (int lane = 0; lane < 8; ++lane) put(group, lane, u[lane]);
  const TrianglePlane pt = TrianglePlane::of(t[0], t[1], t[2]);
  const unsigned bits = rejected_lanes(pt, t, group, margin);
  int differ = 0;
  unsigned want_bits = 0;
  for (int lane = 0; lane < 8; ++lane) {
    const bool want =
        triangles_rejected(pt, t, TrianglePlane::of(u[lane][0], u[lane][1], u[lane][2]), u[lane], margin);
    rejected += want;
    want_bits |= want ? 1u << lane : 0u;
    differ += want != (((bits >> lane) & 1u) != 0);
  }
  for (const unsigned w : wanted)
    differ += __builtin_popcount((rejected_lanes(pt, t, group, margin, w) ^ want_bits) & w);
  return differ;
}

}  // namespace

TEST_CASE("a triangle's float rejections against 8 others at once are triangles_rejected's, lane by lane") {
  // Triangles of leaflet size up to 2 m from the origin, the others shifted by up to twice their
  // size (crossing, touching, apart), slivers, points, shared corners and copies; margins of the
  // exact stage (clearance + kRejectSlack) and a NaN lane.
  std::mt19937 rng(41);
  std::uniform_real_distribution<float> u(-1, 1);
  int differ = 0, rejected = 0, kept = 0;
  for (int trial = 0; trial < 6000; ++trial) {
    const Vec3f base{2.0f * u(rng), 2.0f * u(rng), 1.5f + u(rng)};
    const float size = trial % 2 ? 0.02f : 0.002f;
    Vec3f t[3], others[8][3];
    for (auto& p : t) p = base + Vec3f{u(rng), u(rng), u(rng)} * size;
    for (int lane = 0; lane < 8; ++lane) {
      const Vec3f shift = Vec3f{u(rng), u(rng), u(rng)} * (2 * size * static_cast<float>(lane) / 7.0f);
      for (auto& p : others[lane]) p = base + shift + Vec3f{u(rng), u(rng), u(rng)} * size;
      switch ((trial + lane) % 9) {
        case 0:
          others[lane][2] = others[lane][0] + (others[lane][1] - others[lane][0]) * 0.5f;
          break;                                                             // a sliver
        case 1: others[lane][1] = others[lane][2] = others[lane][0]; break;  // a point
        case 2: others[lane][0] = t[1]; break;                               // a shared corner
        case 3:
          for (int c = 0; c < 3; ++c) others[lane][c] = t[(c + 1) % 3];
          break;  // t itself
        case 4:
          for (int c = 0; c < 3; ++c) others[lane][c] = t[c] + Vec3f{0, 0, size * 0.5f};
          break;  // parallel planes
        default: break;
      }
    }
    if (trial % 50 == 0) others[trial % 8][1].y = std::numeric_limits<float>::quiet_NaN();
    for (const float c : {0.0f, 1e-4f, 0.01f}) {
      int r = 0;
      differ += rejected_differences(t, others, c + kRejectSlack, r,
                                     {1u << (trial % 8), static_cast<unsigned>(rng() & 0xffu)});
      rejected += r, kept += 8 - r;
    }
  }
  CHECK(differ == 0);
  CHECK(rejected > 20000);
  CHECK(kept > 20000);
}

TEST_CASE("the float rejections 8 at a time agree at the last float where they change") {
  // The other triangle slid along a direction (the first triangle's normal, or an edge-cross-edge
  // axis) to the float at which triangles_rejected's answer flips, found by bisection; the lanes
  // hold that position and the floats around it.
  std::mt19937 rng(43);
  std::uniform_real_distribution<float> u(-1, 1);
  int differ = 0, flips = 0, rejected = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Vec3f base{2.0f * u(rng), 2.0f * u(rng), 1.5f + u(rng)};
    const float size = trial % 2 ? 0.02f : 0.002f, margin = (trial % 3 ? 0.0f : 1e-4f) + kRejectSlack;
    Vec3f t[3], q[3];
    for (auto& p : t) p = base + Vec3f{u(rng), u(rng), u(rng)} * size;
    for (auto& p : q) p = base + Vec3f{u(rng), u(rng), u(rng)} * size;
    const Vec3f dir = trial % 2 ? cross(t[1] - t[0], t[2] - t[0]) : cross(t[1] - t[0], q[2] - q[1]);
    const float len = std::sqrt(dot(dir, dir));
    if (!(len > 0)) continue;
    const Vec3f unit = dir * (1.0f / len);
    const auto moved = [&](float s, Vec3f* out) {
      for (int c = 0; c < 3; ++c) out[c] = q[c] + unit * s;
    };
    const TrianglePlane pt = TrianglePlane::of(t[0], t[1], t[2]);
    const auto rejects = [&](float s) {
      Vec3f m[3];
      moved(s, m);
      return triangles_rejected(pt, t, TrianglePlane::of(m[0], m[1], m[2]), m, margin);
    };
    float lo = 0, hi = 4 * size;  // at 0 they overlap often, at 4 sizes they are apart
    if (rejects(lo) || !rejects(hi)) continue;
    for (int step = 0; step < 60 && std::nextafter(lo, hi) < hi; ++step) {
      const float mid = 0.5f * (lo + hi);
      if (mid <= lo || mid >= hi) break;
      (rejects(mid) ? hi : lo) = mid;
    }
    ++flips;
    Vec3f others[8][3];
    float s = lo;
    for (int k = 0; k < 3; ++k) s = std::nextafter(s, -1.0f);
    for (int lane = 0; lane < 8; ++lane, s = std::nextafter(s, 1.0f)) moved(s, others[lane]);
    int r = 0;
    differ += rejected_differences(t, others, margin, r);
    rejected += r;
  }
  CHECK(differ == 0);
  CHECK(flips > 500);
  CHECK(rejected > 1000);
}

TEST_CASE(
    "float bounds of a box of floats are the floats themselves, as the rounding constructor makes them") {
  // posed_touch takes FloatBounds::of_floats for a triangle's box when there is no clearance:
  // the same bounds as FloatBounds' constructor, which corrects any rounding (none here), on
  // signed zeros, tiny, huge and random floats.
  std::mt19937 g(41);
  std::uniform_real_distribution<float> u(-3, 3);
  const float special[] = {0.0f,
                           -0.0f,
                           std::numeric_limits<float>::denorm_min(),
                           -std::numeric_limits<float>::min(),
                           std::numeric_limits<float>::max(),
                           -std::numeric_limits<float>::max(),
                           1e-30f,
                           123456.7f};
  for (int i = 0; i < 20000; ++i) {
    double box[6];
    for (double& v : box)
      v = g() % 5 == 0 ? special[g() % 8] : u(g) * std::pow(10.0f, static_cast<float>(g() % 9) - 4.0f);
    const FloatBounds want(box), got = FloatBounds::of_floats(box);
    CHECK(std::memcmp(want.lo_above, got.lo_above, sizeof want.lo_above) == 0);
    CHECK(std::memcmp(want.hi_below, got.hi_below, sizeof want.hi_below) == 0);
  }
}
