// The capsule rejection of two solids (geometry/solid_bound.hpp): its segment distance is a lower
// bound of the true least distance (found here by a search of its own, in long double) and a
// close one; every posed vertex of a cylinder or sphere mesh lies inside its capsule, under
// rotations, unequal radial scales and sheared columns, far from the plant origin too; organs
// that are not solids, and non-finite transforms, are never rejected.
#include "geometry/prototype.hpp"
#include "geometry/solid_bound.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace canopy;

namespace {

using LD = long double;

LD point_distance(D3 p, D3 u, LD s, D3 q, D3 v, LD t) {
  const LD x = p.x + u.x * s - q.x - v.x * t, y = p.y + u.y * s - q.y - v.y * t,
           z = p.z + u.z * s - q.z - v.z * t;
  return std::sqrt(x * x + y * y + z * z);
}

/// The least distance of two segments by nested ternary searches (the distance is convex in s
/// and t, and so is its minimum over t as a function of s).
LD reference_segment_distance(D3 p, D3 u, D3 q, D3 v) {
  const auto over_t = [&](LD s) {
    LD lo = 0, hi = 1;
    for (int i = 0; i < 200; ++i) {
      const LD a = lo + (hi - lo) / 3, b = hi - (hi - lo) / 3;
      if (point_distance(p, u, s, q, v, a) < point_distance(p, u, s, q, v, b)) hi = b;
      else lo = a;
    }
    return std::min<LD>({point_distance(p, u, s, q, v, lo), point_distance(p, u, s, q, v, 0),
                         point_distance(p, u, s, q, v, 1)});
  };
  LD lo = 0, hi = 1;
  for (int i = 0; i < 200; ++i) {
    const LD a = lo + (hi - lo) / 3, b = hi - (hi - lo) / 3;
    if (over_t(a) < over_t(b)) hi = b;
    else lo = a;
  }
  return std::min<LD>({over_t(lo), over_t(0), over_t(1)});
}

D3 random_unit(std::mt19937_64& g) {
  std::normal_distribution<double> n(0, 1);
  const D3 v{n(g), n(g), n(g)};
  return v * (1 / std::sqrt(dot(v, v)));
}

}  // namespace

TEST_CASE("the segment distance bound never exceeds the least distance, and stays close to it") {
  std::mt19937_64 g(11);
  std::uniform_real_distribution<double> u01(0, 1);
  int parallel = 0, crossing = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const double len_u = trial % 17 == 0 ? 0 : 0.2 * u01(g), len_v = trial % 19 == 0 ? 0 : 0.2 * u01(g);
    const D3 p{u01(g) - 0.5, u01(g) - 0.5, 1 + u01(g)};
    const D3 du = random_unit(g);
    D3 dv = random_unit(g);
    const int kind = trial % 4;
    if (kind == 1) {  // all but parallel: angles from 1e-9 to 1e-3 rad
      const double angle = std::pow(10.0, -9 + 6 * u01(g));
      dv = du * std::cos(angle) + cross(du, random_unit(g)) * std::sin(angle);
      dv = dv * (1 / std::sqrt(dot(dv, dv)));
      if (trial % 8 == 1) dv = du * -1.0;  // exactly anti-parallel
      ++parallel;
    }
    const D3 uu = du * len_u, vv = dv * len_v;
    // The second segment starts near a point of the first: crossing, T-junctions, near misses.
    const D3 near = p + uu * u01(g) + random_unit(g) * (kind == 2 ? 0.0 : 0.02 * u01(g));
    D3 q = kind == 3 ? near - vv * u01(g) : near;
    // All but parallel and crossing midway (an X of a tiny angle): the least distance lies
    // inside both, and the ends are (|u| + |v|) sin / 2 from the other segment.
    if (kind == 1 && trial % 8 == 5) q = p + uu * 0.5 - vv * 0.5 + random_unit(g) * (1e-9 * u01(g));
    crossing += kind == 2;
    const double bound = segments_distance_bound(p, uu, q, vv);
    const LD ref = reference_segment_distance(p, uu, q, vv);
    CHECK_MESSAGE(static_cast<LD>(bound) <= ref + 1e-12L, "trial ", trial, " bound ", bound, " least ",
                  static_cast<double>(ref));
    // Close: within 1e-9 m, the all-but-parallel allowance of 2 (|u| + |v|) sin, and the margin
    // left for the rounding of the lines' closest points (1e-14 (1 + |r| / |u|) / sin^2 of u).
    const D3 n = cross(uu, vv), r = q - p;
    const double sin = len_u > 0 && len_v > 0 ? std::sqrt(dot(n, n)) / (len_u * len_v) : 0;
    double allowance = sin < 1e-5 ? 2 * (len_u + len_v) * sin : 0;
    if (sin >= 1e-5) {
      const double rn = std::sqrt(dot(r, r));
      allowance = (1e-12 + 1e-14 * (1 + rn / len_u) / (sin * sin)) * len_u +
                  (1e-12 + 1e-14 * (1 + rn / len_v) / (sin * sin)) * len_v;
    }
    CHECK_MESSAGE(static_cast<LD>(bound) >= ref - allowance - 1e-9L, "trial ", trial, " bound ", bound,
                  " least ", static_cast<double>(ref));
  }
  CHECK(parallel > 500);
  CHECK(crossing > 500);
}

TEST_CASE("a solid's capsule holds every vertex of its posed mesh") {
  std::mt19937_64 g(5);
  std::uniform_real_distribution<double> u01(0, 1);
  PrototypeLibrary lib;
  for (int trial = 0; trial < 400; ++trial) {
    const PrototypeKind kind = trial % 2 ? PrototypeKind::cylinder : PrototypeKind::sphere;
    const PrototypeMesh& mesh = lib.get(kind, 1 + trial % 4);
    const D3 h = random_unit(g);
    D3 l = cross(h, random_unit(g));
    l = l * (1 / std::sqrt(dot(l, l)));
    const D3 up = cross(h, l);
    const double length = 0.001 + 0.3 * u01(g), r1 = 0.0005 + 0.02 * u01(g);
    // Unequal radial scales and a sheared column on some: the stretch bound must still hold.
    const double r2 = trial % 3 == 0 ? r1 * (0.5 + u01(g)) : r1;
    const D3 shear = trial % 5 == 0 ? h * (0.3 * r1) : D3{0, 0, 0};
    const auto f = [](D3 v) {
      return Vec3f{static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)};
    };
    Affine3f m;
    m.c0 = f(h * (kind == PrototypeKind::cylinder ? length : r1));
    m.c1 = f(l * r1 + shear);
    m.c2 = f(up * r2);
    m.t = f(D3{4 * u01(g) - 2, 4 * u01(g) - 2, 2 * u01(g)});
    const Vec3f d = trial % 4 == 0 ? Vec3f{0.4f, -1.0f, 0} : Vec3f{0, 0, 0};
    Capsule c;
    REQUIRE(solid_capsule(kind, m, d, c));
    const double slack = kSolidRelSlack * c.size + kSolidAbsSlack;
    double worst = -1;
    for (const Vec3f& v : mesh.positions) {
      const Vec3f posed = apply(m, v) + d;  // as the exact test makes it
      const double dist = std::sqrt(segment_segment_dist2(d3(posed), d3(posed), c.p, c.p + c.u));
      worst = std::max(worst, dist - c.radius);
    }
    CHECK_MESSAGE(worst <= slack, "trial ", trial, " a vertex ", worst, " m beyond the capsule");
    // And the capsule is tight around the mesh: exactly so for a rotation times equal radial
    // scales (a vertex lies on its surface), within half its radius for the rest.
    const bool orthogonal = trial % 3 != 0 && trial % 5 != 0;
    CHECK(worst > (orthogonal ? -1e-3 : -0.5) * c.radius - 1e-9);
  }
}

TEST_CASE("only two solids are ever rejected, and never on non-finite transforms") {
  const Affine3f a{{0.1f, 0, 0}, {0, 0.01f, 0}, {0, 0, 0.01f}, {0, 0, 0}};
  const Affine3f far{{0.1f, 0, 0}, {0, 0.01f, 0}, {0, 0, 0.01f}, {0, 0, 1}};
  CHECK(solids_apart(PrototypeKind::cylinder, a, PrototypeKind::cylinder, far, {0, 0, 0}, 0));
  CHECK(solids_apart(PrototypeKind::cylinder, a, PrototypeKind::sphere, far, {0, 0, 0}, 0));
  CHECK_FALSE(solids_apart(PrototypeKind::cylinder, a, PrototypeKind::cylinder, far, {0, 0, 0},
                           2.0f));  // within the clearance
  CHECK_FALSE(solids_apart(PrototypeKind::cylinder, a, PrototypeKind::cylinder, far, {0, 0, -0.99f},
                           0));  // moved onto it
  CHECK_FALSE(solids_apart(PrototypeKind::leaflet, a, PrototypeKind::cylinder, far, {0, 0, 0}, 0));
  CHECK_FALSE(solids_apart(PrototypeKind::cylinder, a, PrototypeKind::disk, far, {0, 0, 0}, 0));
  Affine3f bad = far;
  for (float x : {std::nanf(""), INFINITY}) {
    bad.t.x = x;
    CHECK_FALSE(solids_apart(PrototypeKind::cylinder, a, PrototypeKind::cylinder, bad, {0, 0, 0}, 0));
    bad = far;
    bad.c1.y = x;
    CHECK_FALSE(solids_apart(PrototypeKind::cylinder, a, PrototypeKind::cylinder, bad, {0, 0, 0}, 0));
    bad = far;
  }
}
