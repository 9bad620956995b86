// Resolution: after it, detection from scratch finds no contact involving an organ that may turn
// (or reports each one left with a reason); organs stay attached; turns stay within the joint
// limits; untouched plants and organs are bit-identical; results do not depend on threads.
#include "collision/memory_budget.hpp"
#include "resolution/joints.hpp"
#include "resolution/resolve.hpp"
#include "tests/collision/helpers.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <unistd.h>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <numbers>

using namespace canopy;
using namespace canopy::test;

namespace {

ResolveResult run(Stand& s, int threads = 0, ResolveConfig cfg = {}) {
  auto cpu = make_cpu_backend();
  ResolveRequest req;
  req.detect.threads = threads;
  req.config = cfg;
  const Contacts first = cpu->detect(s, req.detect);
  return resolve(s, *cpu, req, first);
}

bool may_turn(const Stand& s, std::int32_t organ) {
  const KindMask movable = ResolveConfig::default_movable_kinds();
  for (std::int32_t k = organ; k >= 0; k = s.organs[static_cast<std::size_t>(k)].parent) {
    const OrganKind kind = s.organs[static_cast<std::size_t>(k)].kind;
    if (movable[static_cast<std::size_t>(kind)]) return true;
    if (kind != OrganKind::fruit && kind != OrganKind::flower) return false;
  }
  return false;
}

Mat3d frame(const Affine3f& t) {  // the organ's orthonormal frame: columns H, L, U
  const Vec3d c[3] = {normalized(to_double(t.c0)), normalized(to_double(t.c1)), normalized(to_double(t.c2))};
  Mat3d m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      m.m[3 * i + j] = (j == 0   ? c[0]
                        : j == 1 ? c[1]
                                 : c[2])
                               .x *
                           (i == 0) +
                       (j == 0   ? c[0]
                        : j == 1 ? c[1]
                                 : c[2])
                               .y *
                           (i == 1) +
                       (j == 0   ? c[0]
                        : j == 1 ? c[1]
                                 : c[2])
                               .z *
                           (i == 2);
  return m;
}

/// The point p in the frame of transform t (columns may be scaled): solves A x = p - t.
Vec3d local_point(const Affine3f& t, Vec3d p) {
  const Vec3d a = to_double(t.c0), b = to_double(t.c1), c = to_double(t.c2), r = p - to_double(t.t);
  const double det = dot(a, cross(b, c));
  return {dot(r, cross(b, c)) / det, dot(a, cross(r, c)) / det, dot(a, cross(b, r)) / det};
}

Vec3d apply_d(const Affine3f& t, Vec3d x) {
  return to_double(t.c0) * x.x + to_double(t.c1) * x.y + to_double(t.c2) * x.z + to_double(t.t);
}

}  // namespace

TEST_CASE("joints: a turn carries the subtree rigidly and leaves everything else bit-identical") {
  Stand s = random_stand(3, 3);
  Joints j(s);
  const Stand grown = s;
  // A rachis segment of the first compound leaf: it carries leaflets and further segments.
  std::uint32_t k = 0;
  while (s.organs[k].kind != OrganKind::rachis) ++k;
  REQUIRE(j.subtree_end(k) > k + 1);
  const Mat3d r = axis_angle(normalized(Vec3d{1, 2, 3}), 20 * std::numbers::pi / 180);
  j.set_local(k, j.local_after(k, r));
  const auto moved = j.update(s, {k});
  CHECK(moved.size() == j.subtree_end(k) - k);
  CHECK(std::abs(j.angle_deg(k) - 20) < 1e-9);
  for (std::size_t i = 0; i < s.organ_count(); ++i) {
    const bool in = i >= k && i < j.subtree_end(k);
    if (!in) CHECK(std::memcmp(&s.transforms[i], &grown.transforms[i], sizeof(Affine3f)) == 0);
  }
  // The joint stays put; distances within the subtree are kept.
  CHECK(length(to_double(s.transforms[k].t) - to_double(grown.transforms[k].t)) < 1e-7);
  for (std::uint32_t i = k + 1; i < j.subtree_end(k); ++i) {
    const double before = length(to_double(grown.transforms[i].t) - to_double(grown.transforms[k].t));
    const double after = length(to_double(s.transforms[i].t) - to_double(s.transforms[k].t));
    CHECK(std::abs(before - after) < 1e-6);
  }
}

TEST_CASE("resolution leaves no contact involving an organ that may turn, on seeded random stands") {
  std::size_t before = 0, moved = 0;
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    // Rows at default and dense spacing must come out clean; the crowded random clusters of the
    // detection suite (seeds 11, 12: up to 30 plants per m2, some sharing a spot) cannot, and
    // must report what is left.
    const bool crowded = seed > 10;
    Stand s = crowded ? random_stand(seed, 12) : row_stand(seed);
    const Stand grown = s;
    ResolveConfig cfg;
    if (crowded) cfg.max_rounds = 6;
    const ResolveResult r = run(s, 0, cfg);
    before += r.contacts_before;
    moved += r.organs_moved;
    // Detection from scratch.
    auto cpu = make_cpu_backend();
    const Contacts after = cpu->detect(s, DetectRequest{});
    CHECK(after.pairs.size() == r.contacts_after);
    std::size_t listed = 0;
    for (const Contact& c : after.pairs) {
      // Whatever is left is reported, with its reason.
      bool found = false;
      for (const UnresolvedContact& u : r.unresolved) found |= u.contact == c;
      CHECK(found);
      listed += found;
    }
    CHECK(listed == r.unresolved.size());
    // Two plants on one spot cannot come apart; any other stand must come out clean of every
    // contact that a turn could remove.
    const auto same_spot = [&](std::int32_t p, std::int32_t q) {
      return p != q && s.plants[static_cast<std::size_t>(p)].x == s.plants[static_cast<std::size_t>(q)].x &&
             s.plants[static_cast<std::size_t>(p)].y == s.plants[static_cast<std::size_t>(q)].y;
    };
    for (const Contact& c : after.pairs) {
      if (crowded || same_spot(c.plant_a, c.plant_b)) continue;
      INFO("seed " << seed << ": organs " << c.organ_a << " " << c.organ_b);
      CHECK((!may_turn(s, c.organ_a) && !may_turn(s, c.organ_b)));
    }
    for (std::size_t i = 0; i < s.organ_count(); ++i) {
      const Affine3f& t = s.transforms[i];
      for (float v :
           {t.c0.x, t.c0.y, t.c0.z, t.c1.x, t.c1.y, t.c1.z, t.c2.x, t.c2.y, t.c2.z, t.t.x, t.t.y, t.t.z})
        REQUIRE(std::isfinite(v));
    }
    // Attached: each child's base keeps its place in its parent's frame (within 1e-5 m).
    for (std::size_t i = 0; i < s.organ_count(); ++i) {
      const std::int32_t p = s.organs[i].parent;
      if (p < 0) continue;
      const Vec3d at =
          local_point(grown.transforms[static_cast<std::size_t>(p)], to_double(grown.transforms[i].t));
      const Vec3d want = apply_d(s.transforms[static_cast<std::size_t>(p)], at);
      CHECK(length(want - to_double(s.transforms[i].t)) < 1e-5);
    }
    // Joint limits: each organ's orientation relative to its parent moved by at most its limit.
    for (std::size_t i = 0; i < s.organ_count(); ++i) {
      const std::int32_t p = s.organs[i].parent;
      const Mat3d pg = p < 0 ? Mat3d{} : frame(grown.transforms[static_cast<std::size_t>(p)]);
      const Mat3d pn = p < 0 ? Mat3d{} : frame(s.transforms[static_cast<std::size_t>(p)]);
      const Mat3d rel_grown = transpose(pg) * frame(grown.transforms[i]);
      const Mat3d rel_now = transpose(pn) * frame(s.transforms[i]);
      CHECK(rotation_angle_deg(transpose(rel_grown) * rel_now) <= s.joint_limit_deg[i] + 1e-3);
      if (s.organs[i].kind == OrganKind::internode)
        CHECK(rotation_angle_deg(transpose(rel_grown) * rel_now) < 1e-3);
    }
    // Plants with no turned organ are bit-identical.
    std::vector<std::uint8_t> touched(s.plant_count(), 0);
    for (std::size_t i = 0; i < s.organ_count(); ++i)
      if (std::memcmp(&s.transforms[i], &grown.transforms[i], sizeof(Affine3f)) != 0)
        touched[static_cast<std::size_t>(s.organs[i].plant)] = 1;
    std::size_t untouched = 0;
    for (std::uint8_t t : touched) untouched += !t;
    MESSAGE("seed " << seed << ": " << r.contacts_before << " -> " << r.contacts_after << " contacts, "
                    << r.rounds << " rounds, " << r.organs_moved << " turned (max " << r.max_turn_deg
                    << " deg), " << untouched << " plants untouched");
    CHECK(r.max_joint_deg <= 60 + 1e-6);
  }
  CHECK(before > 0);
  CHECK(moved > 0);
}

TEST_CASE("resolution is the same for any thread count") {
  for (std::uint64_t seed : {4u, 5u}) {
    Stand a = row_stand(seed), b = a;
    const ResolveResult ra = run(a, 1), rb = run(b, 2);
    CHECK(ra.contacts_after == rb.contacts_after);
    CHECK(ra.organs_moved == rb.organs_moved);
    CHECK(std::memcmp(a.transforms.data(), b.transforms.data(), a.transforms.size() * sizeof(Affine3f)) == 0);
  }
}

TEST_CASE("two plants on one spot: resolution stops and says what is left and why") {
  GrowRequest req;
  req.grammar = source("grammars/tomato.yaml");
  req.steps = 10;
  PlantPlacement p;
  p.seed = 7;
  req.plants = {p, p};
  Stand s = grow_stand(req);
  ResolveConfig cfg;
  cfg.max_rounds = 5;
  const ResolveResult r = run(s, 0, cfg);
  CHECK_FALSE(r.converged);
  CHECK(r.contacts_after > 0);
  CHECK(r.unresolved.size() == r.contacts_after);
  CHECK(r.rounds <= 5);
  for (const UnresolvedContact& u : r.unresolved) CHECK_FALSE(u.reason.empty());
}

TEST_CASE("organ-level resolution clears the OBBs, and so the exact level too") {
  Stand s = random_stand(4, 8);
  ResolveConfig cfg;
  cfg.level = ContactLevel::organ;
  auto cpu = make_cpu_backend();
  ResolveRequest req;
  req.config = cfg;
  req.detect.level = ContactLevel::organ;
  const Contacts first = cpu->detect(s, req.detect);
  const ResolveResult r = resolve(s, *cpu, req, first);
  const Contacts exact = cpu->detect(s, DetectRequest{});
  for (const Contact& c : exact.pairs) {
    bool listed = false;
    for (const UnresolvedContact& u : r.unresolved) listed |= u.contact == c;
    CHECK(listed);
  }
}

TEST_CASE(
    "re-detection told which organs moved reports exactly the pairs with a moved organ, at the organ and "
    "exact levels") {
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    for (const ContactLevel level : {ContactLevel::organ, ContactLevel::exact}) {
      Stand s = random_stand(200 + seed, 10);
      Joints joints(s);
      auto cpu = make_cpu_backend();
      DetectRequest req;
      req.level = level;
      const Contacts before = cpu->detect(s, req);
      // Turn a few joints by random angles; their subtrees move.
      std::mt19937_64 g(seed);
      std::vector<std::uint32_t> turned;
      for (int k = 0; k < 12; ++k) {
        const auto organ = static_cast<std::uint32_t>(g() % s.organ_count());
        if (s.organs[organ].parent < 0) continue;
        joints.set_local(organ, axis_angle(normalized(Vec3d{1.0 + k, 2.0, -1.0 * k}), 0.3));
        turned.push_back(organ);
      }
      std::sort(turned.begin(), turned.end());
      turned.erase(std::unique(turned.begin(), turned.end()), turned.end());
      const std::vector<std::uint32_t> moved = joints.update(s, turned);
      std::vector<std::uint8_t> moved_flag(s.organ_count(), 0), active(s.plant_count(), 0);
      for (std::uint32_t k : moved)
        moved_flag[k] = 1, active[static_cast<std::size_t>(s.organs[k].plant)] = 1;
      req.active_plants = &active;
      req.moved_organs = &moved_flag;
      const Contacts again = cpu->redetect(s, req, moved);
      // The oracle: detection from scratch, the pairs with a moved organ.
      auto fresh = make_cpu_backend();
      std::vector<Contact> want;
      for (const Contact& c : fresh->detect(s, DetectRequest{level}).pairs)
        if (moved_flag[static_cast<std::size_t>(c.organ_a)] ||
            moved_flag[static_cast<std::size_t>(c.organ_b)])
          want.push_back(c);
      INFO("seed " << seed << " level " << name_of(level));
      CHECK(again.pairs == want);
      CHECK(!moved.empty());
    }
  }
}

TEST_CASE("settings that cannot be met are refused by name, before any work") {
  // Every comparison with NaN is false: a NaN scan step never reached the joint's reach (the scan
  // ran forever), and a NaN clearance let every bound reject every pair (no contact found).
  Stand s = random_stand(2, 3);
  auto cpu = make_cpu_backend();
  const Contacts first = cpu->detect(s, DetectRequest{});
  const double bad[] = {std::nan(""), std::numeric_limits<double>::infinity(), -1.0};
  for (const double v : bad) {
    CAPTURE(v);
    DetectRequest d;
    d.clearance = static_cast<float>(v);
    CHECK_THROWS_WITH_AS(cpu->detect(s, d),
                         doctest::Contains("detection: the clearance must be a finite number"),
                         std::invalid_argument);
    CHECK_THROWS_WITH_AS(cpu->redetect(s, d, {}), doctest::Contains("detection: the clearance"),
                         std::invalid_argument);
    ResolveRequest req;
    req.config.scan_step_deg = v;
    CHECK_THROWS_WITH_AS(resolve(s, *cpu, req, first),
                         doctest::Contains("resolution: the scan step (degrees) must be"),
                         std::invalid_argument);
    req.config = ResolveConfig{};
    req.config.clearance = v;
    CHECK_THROWS_WITH_AS(resolve(s, *cpu, req, first), doctest::Contains("resolution: the clearance must be"),
                         std::invalid_argument);
    req.config = ResolveConfig{};
    req.config.angle_tolerance_deg = v;
    CHECK_THROWS_WITH_AS(resolve(s, *cpu, req, first), doctest::Contains("resolution: the angle tolerance"),
                         std::invalid_argument);
    req.config = ResolveConfig{};
    req.config.kind_weight[static_cast<std::size_t>(OrganKind::petiole)] = v;
    CHECK_THROWS_WITH_AS(resolve(s, *cpu, req, first), doctest::Contains("resolution: the petiole weight"),
                         std::invalid_argument);
  }
  // Past 100 m every organ pair of a field is a contact: refused by the library (Python took it).
  DetectRequest far;
  far.clearance = 100.5f;
  CHECK_THROWS_WITH_AS(cpu->detect(s, far), doctest::Contains("from 0 to 100 (got 100.5)"),
                       std::invalid_argument);
  ResolveRequest far_turn;
  far_turn.config.clearance = 100.5;
  CHECK_THROWS_WITH_AS(resolve(s, *cpu, far_turn, first),
                       doctest::Contains("resolution: the clearance must be"), std::invalid_argument);
  DetectRequest threads;
  threads.threads = -1;
  CHECK_THROWS_AS(cpu->detect(s, threads), std::invalid_argument);
  ResolveRequest rounds;
  rounds.config.max_rounds = 0;
  CHECK_THROWS_AS(resolve(s, *cpu, rounds, first), std::invalid_argument);
  // The stand is as it was: nothing ran.
  CHECK(cpu->detect(s, DetectRequest{}).pairs == first.pairs);
}

TEST_CASE(
    "bent chains: turns spread over petiole and rachis joints stay attached, within limits, and clear the "
    "stand") {
  // Mature tomatoes in a row: large drooping leaves of neighbours and of one plant meet.
  std::size_t bends = 0, joints_bent = 0;
  for (std::uint64_t seed = 1; seed <= 2; ++seed) {
    GrowRequest req;
    req.grammar = source("grammars/tomato_mature.yaml");
    req.steps = 22 + static_cast<int>(seed);
    for (int i = 0; i < 4; ++i) {
      PlantPlacement p;
      p.x = 0.4 * i;  // the default stand's spacing in the row
      p.rotation_deg = 77.0 * i + 13.0 * static_cast<double>(seed);
      p.seed = seed * 10 + static_cast<std::uint64_t>(i);
      req.plants.push_back(p);
    }
    Stand s = grow_stand(req);
    const Stand grown = s;
    const ResolveResult r = run(s);
    bends += r.bends, joints_bent += r.bend_joints;
    MESSAGE("seed " << seed << ": " << r.contacts_before << " -> " << r.contacts_after << " contacts, "
                    << r.bends << " turns bent over " << r.bend_joints << " joints, " << r.kinks
                    << " left at one joint; mean " << r.mean_turn_deg << ", max turn " << r.max_turn_deg
                    << ", largest joint " << r.max_joint_deg << " deg");
    CHECK(r.contacts_before > 0);
    auto cpu = make_cpu_backend();
    const Contacts after = cpu->detect(s, DetectRequest{});
    CHECK(after.pairs.size() == r.contacts_after);
    for (const Contact& c : after.pairs) CHECK((!may_turn(s, c.organ_a) && !may_turn(s, c.organ_b)));
    // Every child's base stays on its parent's joint (its tip, for a segment of a chain) or
    // wherever on its parent it grew, within 1e-5 m.
    std::size_t on_tip = 0;
    for (std::size_t i = 0; i < s.organ_count(); ++i) {
      const std::int32_t p = s.organs[i].parent;
      if (p < 0) continue;
      const Affine3f &gp = grown.transforms[static_cast<std::size_t>(p)],
                     &np = s.transforms[static_cast<std::size_t>(p)];
      const Vec3d at = local_point(gp, to_double(grown.transforms[i].t));
      CHECK(length(apply_d(np, at) - to_double(s.transforms[i].t)) < 1e-5);
      if (s.organs[static_cast<std::size_t>(p)].prototype == PrototypeKind::cylinder &&
          length(to_double(grown.transforms[i].t) - to_double(gp.t) - to_double(gp.c0)) < 1e-6) {
        ++on_tip;
        CHECK(length(to_double(s.transforms[i].t) - to_double(np.t) - to_double(np.c0)) < 1e-5);
      }
    }
    CHECK(on_tip > s.organ_count() / 2);
    // No joint beyond its limit: the organ's orientation relative to its parent, and the joint
    // angles resolution reports.
    for (std::size_t i = 0; i < s.organ_count(); ++i) {
      const std::int32_t p = s.organs[i].parent;
      const Mat3d pg = p < 0 ? Mat3d{} : frame(grown.transforms[static_cast<std::size_t>(p)]);
      const Mat3d pn = p < 0 ? Mat3d{} : frame(s.transforms[static_cast<std::size_t>(p)]);
      const Mat3d rel_grown = transpose(pg) * frame(grown.transforms[i]);
      const Mat3d rel_now = transpose(pn) * frame(s.transforms[i]);
      CHECK(rotation_angle_deg(transpose(rel_grown) * rel_now) <= s.joint_limit_deg[i] + 1e-3);
    }
    CHECK(r.max_joint_deg <= 20 + 1e-6);  // the grammar's limits
  }
  CHECK(bends > 0);
  CHECK(joints_bent >= 2 * bends);
}

TEST_CASE("with one bend joint every turn stays at its joint, as before") {
  Stand a = row_stand(4);
  ResolveConfig one;
  one.bend_joints = 1;
  const ResolveResult ra = run(a, 0, one);
  CHECK(ra.bends == 0);
  CHECK(ra.bend_joints == 0);
  CHECK(ra.organs_moved > 0);
}

TEST_CASE("a chain segment may be asked for what its chain's joints can take together") {
  Stand s = row_stand(4);
  Joints j(s);
  ResolveConfig cfg;
  std::uint32_t k = 0;  // the last rachis segment of the first compound leaf
  while (s.organs[k].kind != OrganKind::rachis || s.organs[k + 1].kind == OrganKind::rachis ||
         s.organs[static_cast<std::size_t>(s.organs[k].parent)].kind != OrganKind::rachis)
    ++k;
  const std::vector<std::uint32_t> chain = bend_chain(s, cfg, k, cfg.bend_joints);
  REQUIRE(chain.size() >= 3);
  for (std::size_t i = 1; i < chain.size(); ++i)
    CHECK(chain[i] == static_cast<std::uint32_t>(s.organs[chain[i - 1]].parent));
  // As grown, every joint has its whole limit of room: m joints take m x the least of them.
  double least = 1e300;
  for (std::uint32_t c : chain) least = std::min<double>(least, s.joint_limit_deg[c]);
  CHECK(chain_reach_deg(s, j, cfg, k) == doctest::Approx(least * static_cast<double>(chain.size())));
  // A joint turned to 10 degrees short of its limit: m joints through it take m x 10 (the
  // mover's own joint alone is the search's own limit, not a spread).
  const double turned = s.joint_limit_deg[chain[1]] - 10;
  j.set_local(chain[1], j.local_after(chain[1], axis_angle(Vec3d{0, 0, 1}, turned * std::numbers::pi / 180)));
  CHECK(chain_reach_deg(s, j, cfg, k) ==
        doctest::Approx(10.0 * static_cast<double>(chain.size())).epsilon(1e-9));
  // No chain for a leaflet, nor with one bend joint.
  std::uint32_t leaflet = 0;
  while (s.organs[leaflet].kind != OrganKind::leaflet) ++leaflet;
  CHECK(chain_reach_deg(s, j, cfg, leaflet) == 0);
  cfg.bend_joints = 1;
  CHECK(chain_reach_deg(s, j, cfg, k) == 0);
}

TEST_CASE("resolution refuses contacts past its memory, with a clear message, before any round") {
  // Eight plants on one spot: kResolutionBytesPerContact for each contact resolution starts from.
  Stand s = on_one_spot(8);
  auto cpu = make_cpu_backend();
  const Contacts c = cpu->detect(s, DetectRequest{});
  ResolveRequest rr;
  rr.detect.memory_limit =
      static_cast<std::size_t>(static_cast<double>(c.pairs.size()) * kResolutionBytesPerContact) - 1;
  rr.config.max_rounds = 1;
  CHECK(failure([&] {
          resolve(s, *cpu, rr, cpu->detect(s, DetectRequest{}));
        }).starts_with(fmt::format("resolving {} contacts needs about", c.pairs.size())));
}

TEST_CASE("resolution stops with a clear message when its candidates outgrow the memory") {
  // One petiole chain of 800 segments coiled on itself (a vine): every loop meets every other,
  // and each candidate turn carries the chain beyond it. Its 25,000 contacts pass the per-contact
  // estimate, but the candidates would take about 1 GB; a budget of 1.2 x the estimate stops
  // the round as it grows past 90 % of it, instead of running the machine out of memory.
  char name[] = "/tmp/canopy-coil-XXXXXX";
  const int fd = mkstemp(name);
  REQUIRE(fd >= 0);
  close(fd);
  std::ofstream(name) << "axiom: A\nsteps: 800\norgans:\n  P: {prototype: cylinder, kind: petiole}\n"
                         "productions:\n  - \"A -> P(0.01,0.002)+(10)A\"\n";
  GrowRequest req;
  req.grammar = name;
  req.plants.resize(1);
  Stand s = grow_stand(req);
  std::remove(name);
  auto cpu = make_cpu_backend();
  const Contacts c = cpu->detect(s, DetectRequest{});
  REQUIRE(c.pairs.size() > 20000);
  ResolveRequest rr;
  rr.detect.memory_limit =
      static_cast<std::size_t>(1.2 * static_cast<double>(c.pairs.size()) * kResolutionBytesPerContact);
  rr.config.max_rounds = 1;
  CHECK(failure([&] { resolve(s, *cpu, rr, c); }).starts_with("resolution's candidate turns grew past the "));
}
