// swept_reach bounds where a plant's organs can be after any turns: every corner of every organ
// box stays within it horizontally when random joints turn by any angle (not only within limits).
#include "resolution/joints.hpp"
#include "resolution/resolve_policy.hpp"
#include "resolution/swept_reach.hpp"
#include "geometry/obb.hpp"
#include "tests/collision/helpers.hpp"

#include <cmath>
#include <numbers>

using namespace canopy;
using namespace canopy::test;

TEST_CASE("swept reach: no organ box leaves it under random turns of any size") {
  const KindMask movable = ResolveConfig::default_movable_kinds();
  PrototypeLibrary lib;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    Stand s = random_stand(seed, 4);
    std::vector<double> reach(s.plant_count());
    for (std::size_t p = 0; p < s.plant_count(); ++p) reach[p] = swept_reach(s, lib, p, movable);
    Joints joints(s);
    std::mt19937_64 g(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<std::uint32_t> turned;
    for (std::uint32_t k = 0; k < s.organ_count(); ++k) {
      if (!movable[static_cast<std::size_t>(s.organs[k].kind)] || g() % 3) continue;
      const Vec3d axis = normalized(Vec3d{u(g), u(g), u(g)});
      joints.set_local(k, axis_angle(axis, std::numbers::pi * u(g)));
      turned.push_back(k);
    }
    const auto moved = joints.update(s, turned);
    CHECK(!moved.empty());
    double worst = 0;  // the largest share of its bound a plant's box corner reaches
    for (std::size_t k = 0; k < s.organ_count(); ++k) {
      const OrganRecord& r = s.organs[k];
      const Obb b = make_obb(s.transforms[k], lib.get(r).box, 0);
      for (int c = 0; c < 8; ++c) {
        Vec3f q = b.centre;
        for (int a = 0; a < 3; ++a) q = q + b.axis[a] * (((c >> a) & 1) ? b.half[a] : -b.half[a]);
        const double d = std::hypot(static_cast<double>(q.x), static_cast<double>(q.y));
        worst = std::max(worst, d / reach[static_cast<std::size_t>(r.plant)]);
      }
    }
    CHECK(worst <= 1.0 + 1e-6);
    CHECK(worst > 0.3);  // and it is not a vacuous bound
  }
}
