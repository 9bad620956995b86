// The turn search's attempt against brute force: a turn of a mover's subtree about its joint is
// accepted exactly when, at the turned pose, no moving organ comes within the clearance of an
// organ it met and (a strict search) none comes within the detection clearance of any organ of
// the stand that was clear of the subtree before, inside the joint limit. The search finds the
// organs to test through the neighbourhood grid, organ runs and chord bounds, gathered for the
// turns tried so far; the oracle looks at every organ of the stand.
#include "resolution/joints.hpp"
#include "resolution/neighbourhood.hpp"
#include "resolution/resolve_policy.hpp"
#include "resolution/turn_search.hpp"
#include "tests/collision/helpers.hpp"

#include <algorithm>
#include <numbers>

using namespace canopy;
using namespace canopy::test;

namespace {

constexpr double kRad = std::numbers::pi / 180;

struct Setup {
  Stand stand;
  Joints joints;
  PrototypeLibrary lib;
  ResolveConfig config;
  KindMask collide = default_collide_kinds();
  std::vector<Obb> boxes;
  std::vector<Contact> contacts;
  ContactGraph touching;
  explicit Setup(Stand s) : stand(std::move(s)), joints(stand) {
    for (std::size_t k = 0; k < stand.organ_count(); ++k) {
      const OrganRecord& r = stand.organs[k];
      boxes.push_back(make_obb(stand.transforms[k], lib.get(r).box, 0));
    }
    DetectRequest req;
    req.clearance = 0;
    contacts = make_cpu_backend()->detect(stand, req).pairs;
    touching.build(stand.organ_count(), contacts);
  }
};

/// The oracle: whether turning `c`'s subtree by rotation r clears what the search asks for.
bool brute_attempt(Setup& w, const TurnSearch& search, const TurnSearch::Candidate& c, const Mat3d& r,
                   double deg, ExactScratch& scratch) {
  const Stand& s = w.stand;
  // Within the mover's joint limit, or (a chain segment) within what a spread over its chain can
  // take (resolution/bend_chain.hpp).
  if (rotation_angle_deg(Joints::local_after(c.frame, r)) > s.joint_limit_deg[c.mover] &&
      !(deg <= c.chain_deg))
    return false;
  const Motion turn = rotation_about(c.joint, r);
  const auto met = c.keep.begin() + static_cast<std::ptrdiff_t>(c.met_count);
  for (std::int32_t x : c.moving) {
    const Affine3f tx = apply(turn, s.transforms[static_cast<std::size_t>(x)]);
    const Obb& ox = w.boxes[static_cast<std::size_t>(x)];
    const Vec3d cx = apply(turn, to_double(ox.centre));
    const std::int32_t px = s.organs[static_cast<std::size_t>(x)].plant;
    for (std::size_t k = 0; k < s.organ_count(); ++k) {
      const auto y = static_cast<std::int32_t>(k);
      if (w.joints.holds(c.mover, y) || !w.collide[static_cast<std::size_t>(s.organs[k].kind)]) continue;
      if (adjacent(s.organs[static_cast<std::size_t>(x)], x, s.organs[k], y)) continue;
      const bool is_met = std::binary_search(c.keep.begin(), met, y);
      if (!is_met && !c.strict) continue;
      // Organs touching the subtree before the turn are other contacts' business.
      bool busy = false;
      for (std::int32_t m : c.moving)
        for (std::uint32_t e = w.touching.first[static_cast<std::size_t>(m)];
             e < w.touching.first[static_cast<std::size_t>(m) + 1]; ++e)
          busy |= w.touching.with[e] == y;
      if (!is_met && busy) continue;
      const float gap = is_met ? search.clearance : search.detect_clearance;
      // Bounding spheres (the OBB's), in x's plant frame: farther apart, they cannot touch.
      const Vec3f off = s.organs[k].plant == px ? Vec3f{0, 0, 0} : plant_offset(s, px, s.organs[k].plant);
      const Vec3d cy = to_double(w.boxes[k].centre + off);
      if (length(cy - cx) > ox.radius + w.boxes[k].radius + 2.0 * gap + 1e-4) continue;
      const Affine3f& ty = s.transforms[k];
      const bool touch = x < y ? organs_touch_at(s, w.lib, x, tx, y, ty, gap, scratch)
                               : organs_touch_at(s, w.lib, y, ty, x, tx, gap, scratch);
      if (touch) return false;
    }
  }
  return true;
}

}  // namespace

TEST_CASE(
    "turn search: an attempt clears exactly what brute force over the whole stand says (strict and "
    "relaxed)") {
  std::size_t attempts = 0, accepted = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    Setup w(random_stand(100 + seed, 10));
    if (w.contacts.empty()) continue;
    w.config.clearance = seed % 2 ? 1e-4 : 0;
    const float detect_clearance = seed % 3 == 0 ? 5e-5f : 0.f;
    Neighbourhood near(w.stand, w.boxes, 1);
    const TurnSearch search{w.stand,
                            w.joints,
                            w.lib,
                            w.config,
                            w.collide,
                            near,
                            w.boxes,
                            w.touching,
                            static_cast<float>(std::max<double>(w.config.clearance, detect_clearance)),
                            detect_clearance};
    std::mt19937_64 g(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    ExactScratch scratch, oracle_scratch;
    for (std::size_t ci = 0; ci < w.contacts.size(); ci += 1 + w.contacts.size() / 12) {
      std::string why;
      const std::vector<std::uint32_t> movers =
          candidate_movers(w.stand, w.joints, w.contacts[ci], w.config, why);
      for (std::size_t mi = 0; mi < movers.size() && mi < 3; ++mi) {
        const std::uint32_t m = movers[mi];
        MetPairs met;
        for (const Contact& k : w.contacts)
          if (w.joints.holds(m, k.organ_a) != w.joints.holds(m, k.organ_b))
            met.emplace_back(k.organ_a, k.organ_b);
        for (bool strict : {true, false}) {
          TurnSearch::Candidate c = search.prepare(m, met, strict);
          // Angles growing and shrinking on one candidate (its neighbours gathered for small
          // turns first, then again for larger ones), on its own axes and random ones.
          for (int t = 0; t < 24; ++t) {
            const double deg = t < 16 ? (t + 1) * 0.07 * c.reach_deg : (24 - t) * 0.05 * c.reach_deg;
            // The candidate's own axes by index too, so that each starts from what blocked it last.
            const int own = t % 3 == 0 ? -1 : static_cast<int>(static_cast<std::size_t>(t) % c.axes.size());
            Vec3d axis = own < 0 ? Vec3d{u(g), u(g), u(g)} : c.axes[static_cast<std::size_t>(own)];
            if (length(axis) < 0.1) axis = Vec3d{0, 0, 1};
            axis = normalized(axis);
            Mat3d local;
            const bool got = search.attempt(c, axis, deg, local, scratch, own);
            const bool want = brute_attempt(w, search, c, axis_angle(axis, deg * kRad), deg, oracle_scratch);
            INFO("seed " << seed << " mover " << m << (strict ? " strict" : " relaxed") << " axis " << t
                         << " at " << deg << " deg");
            CHECK(got == want);
            ++attempts;
            accepted += got;
          }
        }
      }
    }
  }
  MESSAGE(attempts << " attempts, " << accepted << " accepted");
  CHECK(attempts > 200);
  CHECK(accepted > 20);
  CHECK(accepted < attempts);
}
