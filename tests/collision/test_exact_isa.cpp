// The exact stage's two functions built twice (collision/lanes/isa.hpp): posing an organ and testing
// two posed organs give the same bits from the build target's code and from x86-64-v4's, on every
// organ pair of seeded random stands whose OBBs overlap (and on every such pair a few degrees
// turned, and with clearances), with and without witnesses. Where the CPU has no AVX-512 only
// the build target's code can run; the test says so.
#include "collision/backend.hpp"
#include "collision/exact.hpp"
#include "geometry/motion.hpp"
#include "tests/collision/helpers.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <numbers>

using namespace canopy;
using namespace canopy::test;

namespace {

bool same_pose(const PosedOrgan& x, const PosedOrgan& y) {
  return x.tri_lanes.size() == y.tri_lanes.size() &&
         std::memcmp(x.tri_lanes.data(), y.tri_lanes.data(), x.tri_lanes.size() * sizeof(float)) == 0 &&
         std::memcmp(x.box, y.box, sizeof x.box) == 0 && std::memcmp(&x.obb, &y.obb, sizeof x.obb) == 0 &&
         x.solid == y.solid;
}

bool same_witness(const Witness& x, const Witness& y) {
  return std::memcmp(x.tri_a, y.tri_a, sizeof x.tri_a) == 0 &&
         std::memcmp(x.tri_b, y.tri_b, sizeof x.tri_b) == 0 && x.latest == y.latest;
}

/// Transform t turned by `deg` degrees about the vertical through its origin, as resolution turns
/// an organ about its joint (geometry/motion.hpp).
Affine3f turned(const Affine3f& t, double deg) {
  const double rad = deg * std::numbers::pi / 180;
  return apply(rotation_about(to_double(t.t), axis_angle(Vec3d{0, 0, 1}, std::cos(rad), std::sin(rad))), t);
}

}  // namespace

TEST_CASE("posing and the posed test give the same bits from the build target's code and x86-64-v4's") {
  if (!cpu_has_x86_64_v4()) {
    MESSAGE(
        "this CPU has no AVX-512: only the build target's code runs here (posed_touch_as(Isa::x86_64_v4) not "
        "compared)");
    return;
  }
  auto cpu = make_cpu_backend();
  PrototypeLibrary lib;
  ExactScratch scratch;
  std::size_t pairs = 0, touching = 0, with_clearance = 0;
  for (std::uint64_t seed = 70; seed <= 75; ++seed) {
    const Stand s = random_stand(seed, 8);
    DetectRequest req;
    req.level = ContactLevel::organ;
    req.collide = parse_collide_kinds("all");
    for (const Contact& c : cpu->detect(s, req).pairs) {
      const std::int32_t a = c.organ_a, b = c.organ_b;
      const OrganRecord& ra = s.organs[static_cast<std::size_t>(a)];
      const OrganRecord& rb = s.organs[static_cast<std::size_t>(b)];
      const PrototypeMesh& ma = lib.get(ra);
      const PrototypeMesh& mb = lib.get(rb);
      for (const double deg : {0.0, 3.0}) {
        const Affine3f ta = s.transforms[static_cast<std::size_t>(a)];
        const Affine3f tb = turned(s.transforms[static_cast<std::size_t>(b)], deg);
        PosedOrgan pa[2], pb[2];
        for (int k = 0; k < 2; ++k) {
          const Isa isa = k == 0 ? Isa::build_target : Isa::x86_64_v4;
          pa[k].pose_as(isa, s, ma, a, ta, ra.plant, ra.plant);
          pb[k].pose_as(isa, s, mb, b, tb, rb.plant, ra.plant);
        }
        REQUIRE(same_pose(pa[0], pa[1]));
        REQUIRE(same_pose(pb[0], pb[1]));
        for (const float clearance : {0.0f, 0.002f}) {
          Witness w[2];
          bool touch[2], again[2];
          for (int k = 0; k < 2; ++k) {
            const Isa isa = k == 0 ? Isa::build_target : Isa::x86_64_v4;
            touch[k] = posed_touch_as(isa, pa[0], pb[0], clearance, scratch, &w[k]);
            again[k] =
                posed_touch_as(isa, pa[0], pb[0], clearance, scratch, &w[k]);  // from the witness this time
          }
          CHECK(touch[0] == touch[1]);
          CHECK(again[0] == again[1]);
          CHECK(touch[0] == again[0]);
          CHECK(same_witness(w[0], w[1]));
          CHECK(posed_touch_as(Isa::build_target, pa[0], pb[0], clearance, scratch, nullptr) ==
                posed_touch_as(Isa::x86_64_v4, pa[0], pb[0], clearance, scratch, nullptr));
          ++pairs;
          touching += touch[0];
          with_clearance += clearance > 0 && touch[0];
        }
      }
    }
  }
  MESSAGE("pairs compared: " << pairs << ", touching " << touching << " (" << with_clearance
                             << " with a clearance)");
  CHECK(pairs > 2000);
  CHECK(touching > 200);
  CHECK(touching < pairs);
}
