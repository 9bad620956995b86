// Bounding volumes: every vertex inside its organ's OBB and its cluster's LCD boxes and plant
// bound; OBB and LCD overlap against a brute-force separating-axis test over all 15 axes; refit.
#include "collision/mbvt.hpp"
#include "collision/mbvt_fit.hpp"
#include "geometry/organ_mesh.hpp"
#include "helpers.hpp"

#include <cmath>
#include <cstring>
#include <set>

using namespace canopy;
using namespace canopy::test;

namespace {

/// Brute force: project both boxes' corners on all 15 candidate axes (skipping vanished ones).
bool sat_brute(const Vec3f a_axes[3], const Vec3f a_corners[8], const Vec3f b_axes[3],
               const Vec3f b_corners[8]) {
  std::vector<D3> axes;
  for (int i = 0; i < 3; ++i) axes.push_back(d3(a_axes[i])), axes.push_back(d3(b_axes[i]));
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) axes.push_back(cross(d3(a_axes[i]), d3(b_axes[j])));
  for (const D3& ax : axes) {
    if (dot(ax, ax) < 1e-18) continue;  // parallel edges: no axis
    double alo = 1e300, ahi = -1e300, blo = 1e300, bhi = -1e300;
    for (int k = 0; k < 8; ++k) {
      const double pa = dot(ax, d3(a_corners[k])), pb = dot(ax, d3(b_corners[k]));
      alo = std::min(alo, pa), ahi = std::max(ahi, pa), blo = std::min(blo, pb), bhi = std::max(bhi, pb);
    }
    if (alo > bhi || blo > ahi) return false;
  }
  return true;
}

Obb random_obb(std::mt19937& g, bool axis_aligned) {
  std::uniform_real_distribution<float> u(-1, 1), h(0.01f, 0.6f);
  Vec3f x{1, 0, 0}, y{0, 1, 0};
  if (!axis_aligned) {
    x = Vec3f{u(g), u(g), u(g)};
    x = x * (1 / length(x));
    Vec3f t{u(g), u(g), u(g)};
    y = cross(x, t);
    y = y * (1 / length(y));
  }
  Obb o;
  o.centre = {u(g), u(g), u(g)};
  o.axis[0] = x, o.axis[1] = y, o.axis[2] = cross(x, y);
  for (float& e : o.half) e = h(g);
  set_radius(o);
  return o;
}

}  // namespace

TEST_CASE("OBB overlap agrees with the brute-force 15-axis test, parallel boxes included") {
  std::mt19937 g(3);
  int overlaps = 0, agree = 0, n = 0;
  for (int i = 0; i < 20000; ++i) {
    const bool parallel = i % 3 == 0;
    const Obb a = random_obb(g, parallel), b = random_obb(g, parallel);
    Vec3f ca[8], cb[8];
    obb_corners(a, ca);
    obb_corners(b, cb);
    const bool want = sat_brute(a.axis, ca, b.axis, cb);
    const bool got = obb_overlap(a, b, {0, 0, 0});
    overlaps += want;
    agree += want == got;
    ++n;
    if (want) CHECK(got);  // never a miss
  }
  CHECK(agree == n);
  CHECK(overlaps > 2000);
}

/// An LCD box at angle `ang` whose extents along each axis are centred within +-spread and
/// half-sized min_half + up to half_range.
Lcd random_lcd(std::mt19937& g, float ang, float spread, float min_half, float half_range) {
  std::uniform_real_distribution<float> u(-1, 1);
  Lcd l;
  l.ax = std::cos(ang), l.ay = std::sin(ang);
  for (int d = 0; d < 3; ++d) {
    const float c = spread * u(g), e = min_half + half_range * std::fabs(u(g));
    l.lo[d] = c - e, l.hi[d] = c + e;
  }
  return l;
}

TEST_CASE("LCD overlap agrees with the brute-force test of the same boxes as OBBs") {
  std::mt19937 g(5);
  std::uniform_real_distribution<float> u(-1, 1);
  int agree = 0, n = 0, overlaps = 0;
  for (int i = 0; i < 20000; ++i) {
    Lcd l[2];
    Vec3f axes[2][3], corners[2][8];
    for (int k = 0; k < 2; ++k) {
      l[k] = random_lcd(g, i % 4 == 0 ? 0.3f : u(g) * 3.14159f, 1.0f, 0.05f,
                        0.5f);  // every fourth pair parallel
      axes[k][0] = {l[k].ax, l[k].ay, 0}, axes[k][1] = {-l[k].ay, l[k].ax, 0}, axes[k][2] = {0, 0, 1};
      for (int c = 0; c < 8; ++c) {
        const float su = (c & 1) ? l[k].hi[0] : l[k].lo[0], sv = (c & 2) ? l[k].hi[1] : l[k].lo[1],
                    sz = (c & 4) ? l[k].hi[2] : l[k].lo[2];
        corners[k][c] = axes[k][0] * su + axes[k][1] * sv + Vec3f{0, 0, sz};
      }
    }
    const bool want = sat_brute(axes[0], corners[0], axes[1], corners[1]);
    const bool got = lcd_overlap(l[0], l[1], {0, 0, 0});
    overlaps += want;
    agree += want == got;
    ++n;
    if (want) CHECK(got);
  }
  CHECK(agree == n);
  CHECK(overlaps > 2000);
}

TEST_CASE("an empty LCD box meets nothing, kept as it is or centred") {
  std::mt19937 g(9);
  std::uniform_real_distribution<float> u(-1, 1);
  const Lcd empty;
  const LcdCentred empty_centred = lcd_centred(empty);
  int met = 0;
  for (int i = 0; i < 2000; ++i) {
    const Lcd l = random_lcd(g, u(g) * 3.14159f, 1.0f, 0.05f, 0.5f);
    const Vec3f off{u(g), u(g), u(g)};
    CHECK_FALSE(lcd_overlap(empty, l, off));
    CHECK_FALSE(lcd_overlap(l, empty, off));
    CHECK_FALSE(lcd_overlap(empty_centred, lcd_centred(l), off));
    CHECK_FALSE(lcd_overlap(lcd_centred(l), empty_centred, off));
    met += lcd_overlap(lcd_centred(l), lcd_centred(l), off);  // the test is not always false
  }
  CHECK(met > 100);
}

TEST_CASE(
    "every vertex lies in its organ's OBB, its cluster's LCD and axis-aligned boxes and its plant's bounds") {
  const Stand s = random_stand(7);
  PrototypeLibrary lib;
  MbvtConfig cfg;
  cfg.collide = parse_collide_kinds("all");
  const Mbvt m = build_mbvt(s, lib, cfg);
  OrganMesh mesh;
  std::vector<std::int32_t> node_of_leaf_organ(s.organ_count(), -1);
  for (const Cluster& c : m.clusters)
    for (std::uint32_t n = c.first_node; n < c.first_node + c.node_count; ++n)
      for (std::uint32_t k = m.nodes[n].first; k < m.nodes[n].first + m.nodes[n].count; ++k) {
        const std::uint32_t organ = m.cluster_organs[k];
        organ_mesh(s, organ, lib, mesh, true);
        for (const Vec3f& v : mesh.positions) {
          Lcd point;
          point.ax = m.nodes[n].box.ax, point.ay = m.nodes[n].box.ay;
          lcd_add(point, v);
          for (int d = 0; d < 3; ++d) {
            CHECK(point.lo[d] >= m.nodes[n].box.lo[d]);
            CHECK(point.hi[d] <= m.nodes[n].box.hi[d]);
          }
        }
      }
  const auto inside = [](Vec3f v, const Box3f& b) {
    return v.x >= b.lo.x && v.x <= b.hi.x && v.y >= b.lo.y && v.y <= b.hi.y && v.z >= b.lo.z && v.z <= b.hi.z;
  };
  for (std::uint32_t ci = 0; ci < m.clusters.size(); ++ci) {
    const Cluster& c = m.clusters[ci];
    const PlantBound& pb = m.plants[static_cast<std::size_t>(c.plant)];
    CHECK(m.lanes.clusters
              .get(m.lanes.cluster_first[static_cast<std::size_t>(c.plant)] + (ci - pb.first_cluster))
              .lo.x == c.box.lo.x);
    const LcdCentred root = lcd_centred(m.nodes[c.root].box);
    CHECK(std::memcmp(&m.lanes.roots[ci], &root, sizeof root) == 0);  // the root's LCD box, centred
    const LcdCentred root_lane = m.lanes.root_lanes.get(
        m.lanes.cluster_first[static_cast<std::size_t>(c.plant)] + (ci - pb.first_cluster));
    CHECK(std::memcmp(&root_lane, &root, sizeof root) == 0);  // and in the plant's LCD lanes
    // The root spans the cluster's organs (the CPU pass takes a one-block cluster's span from it).
    CHECK(m.nodes[c.root].first == c.first);
    CHECK(m.nodes[c.root].count == c.count);
    for (std::uint32_t k = c.first; k < c.first + c.count; ++k) {
      organ_mesh(s, m.cluster_organs[k], lib, mesh, true);
      const Box3f organ_box = m.lanes.organs.get(m.lanes.organ_first[ci] + (k - c.first));
      for (const Vec3f& v : mesh.positions) {
        CHECK(inside(v, c.box));
        CHECK(inside(v, pb.box));
        CHECK(inside(v, organ_box));  // the organ's axis-aligned box in its lane (obb_aabb)
        CHECK(inside(v, m.lanes.pass[ci].around));
      }
    }
  }
  for (std::size_t id = 0; id < s.organ_count(); ++id) {
    organ_mesh(s, id, lib, mesh, true);
    const Obb& o = m.obbs[id];
    const PlantBound& pb = m.plants[static_cast<std::size_t>(s.organs[id].plant)];
    for (const Vec3f& v : mesh.positions) {
      const Vec3f d = v - o.centre;
      for (int k = 0; k < 3; ++k) CHECK(std::fabs(dot(d, o.axis[k])) <= o.half[k]);
      CHECK(std::hypot(v.x, v.y) <= pb.radius);
      CHECK(v.z >= pb.zlo);
      CHECK(v.z <= pb.zhi);
    }
  }
}

TEST_CASE(
    "the axis-aligned pre-test never rejects LCD boxes that lcd_overlap accepts, touching ones included") {
  std::mt19937 g(11);
  std::uniform_real_distribution<float> u(-1, 1);
  int overlapping = 0, apart = 0, rejected = 0;
  for (int i = 0; i < 20000; ++i) {
    Lcd l[2];
    // Every fourth pair parallel, every fourth axis-aligned (where the boxes are tightest).
    for (int k = 0; k < 2; ++k)
      l[k] = random_lcd(g, i % 4 == 0 ? 0.3f : i % 4 == 1 ? 0.0f : u(g) * 3.14159f, 0.3f, 0.01f, 0.3f);
    // An offset along a random direction, scaled to where lcd_overlap flips (bisection), then
    // a hair either side of it, and a random scale.
    const Vec3f dir{u(g), u(g), i % 3 == 0 ? 0.0f : 0.5f * u(g)};
    float lo = 0, hi = 8;
    for (int it = 0; it < 60; ++it) {
      const float mid = 0.5f * (lo + hi);
      (lcd_overlap(l[0], l[1], dir * mid) ? lo : hi) = mid;
    }
    const Box3f a = lcd_aabb(l[0]), b = lcd_aabb(l[1]);
    for (float t : {lo, hi, lo * (1 - 1e-6f), hi * (1 + 1e-6f), 0.5f * lo, 1.5f * hi, 4 * std::fabs(u(g))}) {
      const Vec3f off = dir * t;
      const bool meet = lcd_overlap(l[0], l[1], off), pre = boxes_meet(a, b, off);
      INFO("pair " << i << " scale " << t);
      if (meet) CHECK(pre);
      overlapping += meet;
      apart += !meet;
      rejected += !pre;
    }
  }
  CHECK(overlapping > 20000);
  CHECK(rejected > apart / 4);  // the pre-test does reject: not a test that cannot fail
  Lcd empty;
  CHECK_FALSE(boxes_meet(lcd_aabb(empty), lcd_aabb(empty), {0, 0, 0}));
}

TEST_CASE("refit after organs turn equals a rebuild of the same tree") {
  Stand s = random_stand(9);
  PrototypeLibrary lib;
  Mbvt m = build_mbvt(s, lib, MbvtConfig{});
  std::vector<std::uint32_t> moved;
  for (std::uint32_t id = 5; id < s.organ_count(); id += 17) {
    Affine3f& t = s.transforms[id];
    const float c = std::cos(0.3f), sn = std::sin(0.3f);
    const auto rot = [&](Vec3f v) { return Vec3f{c * v.x - sn * v.y, sn * v.x + c * v.y, v.z}; };
    t.c0 = rot(t.c0), t.c1 = rot(t.c1), t.c2 = rot(t.c2);
    moved.push_back(id);
  }
  refit_mbvt(m, s, lib, moved);
  const Mbvt fresh = build_mbvt(s, lib, MbvtConfig{});
  for (std::uint32_t id : moved) CHECK(m.obbs[id].centre.x == fresh.obbs[id].centre.x);
  // Organ lanes are made from the OBBs alone: the refit's are the rebuild's, bit for bit.
  CHECK(m.lanes.organ_first == fresh.lanes.organ_first);
  REQUIRE(m.lanes.organs.data.size() == fresh.lanes.organs.data.size());
  CHECK(std::memcmp(m.lanes.organs.data.data(), fresh.lanes.organs.data.data(),
                    m.lanes.organs.data.size() * sizeof(float)) == 0);
  for (std::size_t c = 0; c < m.clusters.size(); ++c) {
    CHECK(m.lanes.pass[c].around.lo.y == fresh.lanes.pass[c].around.lo.y);
    // The pass records hold the refit tree's own fields.
    for (const Mbvt* t : {static_cast<const Mbvt*>(&m), &fresh}) {
      const PassCluster& pc = t->lanes.pass[c];
      CHECK(std::memcmp(&pc.box, &t->clusters[c].box, sizeof(Box3f)) == 0);
      CHECK(pc.first == t->clusters[c].first);
      CHECK(pc.count == t->clusters[c].count);
      CHECK(pc.lane == t->lanes.organ_first[c]);
      CHECK(pc.has_free == t->cluster_has_free[c]);
    }
    // The refit's root boxes are made again: from its nodes' (the refit keeps the axes, so
    // they need not equal a fresh build's).
    const LcdCentred root = lcd_centred(m.nodes[m.clusters[c].root].box);
    CHECK(std::memcmp(&m.lanes.roots[c], &root, sizeof root) == 0);
    const PlantBound& pb = m.plants[static_cast<std::size_t>(m.clusters[c].plant)];
    const LcdCentred root_lane = m.lanes.root_lanes.get(
        m.lanes.cluster_first[static_cast<std::size_t>(m.clusters[c].plant)] + (c - pb.first_cluster));
    CHECK(std::memcmp(&root_lane, &root, sizeof root) == 0);
    CHECK(m.lanes.clusters
              .get(m.lanes.cluster_first[static_cast<std::size_t>(m.clusters[c].plant)] +
                   (c - pb.first_cluster))
              .hi.z == m.clusters[c].box.hi.z);
  }
  // Boxes contain what they must (axes kept from the first build, so not equal to the fresh ones).
  OrganMesh mesh;
  for (std::uint32_t id : moved) {
    if (!m.takes_part[id]) continue;
    organ_mesh(s, id, lib, mesh, true);
    for (const Vec3f& v : mesh.positions)
      CHECK(std::hypot(v.x, v.y) <= m.plants[static_cast<std::size_t>(s.organs[id].plant)].radius);
  }
}

namespace {

template <typename V>
bool same_bytes(const V& a, const V& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0);
}

/// Every array of two trees, byte for byte.
bool same_tree(const Mbvt& a, const Mbvt& b) {
  bool same = same_bytes(a.obbs, b.obbs) && same_bytes(a.takes_part, b.takes_part) &&
              same_bytes(a.cluster_organs, b.cluster_organs) && same_bytes(a.free_after, b.free_after) &&
              same_bytes(a.cluster_has_free, b.cluster_has_free) &&
              same_bytes(a.plant_has_free, b.plant_has_free) && same_bytes(a.clusters, b.clusters) &&
              same_bytes(a.nodes, b.nodes) && same_bytes(a.plants, b.plants) &&
              a.max_radius == b.max_radius && same_bytes(a.lanes.organ_first, b.lanes.organ_first) &&
              same_bytes(a.lanes.pass, b.lanes.pass) && same_bytes(a.lanes.roots, b.lanes.roots) &&
              same_bytes(a.lanes.cluster_first, b.lanes.cluster_first);
  return same && same_bytes(a.lanes.organs.data, b.lanes.organs.data) &&
         same_bytes(a.lanes.clusters.data, b.lanes.clusters.data) &&
         same_bytes(a.lanes.root_lanes.data, b.lanes.root_lanes.data);
}

}  // namespace

TEST_CASE("a tree rebuilt in place over another stand's equals a fresh build, byte for byte") {
  // Larger, smaller and other stands in turn, with other settings: nothing of the last tree
  // may show through.
  PrototypeLibrary lib;
  Mbvt reused;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const Stand s = seed % 2 ? random_stand(seed, 4 + 6 * static_cast<int>(seed % 3)) : row_stand(seed);
    MbvtConfig cfg;
    if (seed % 3 == 0) cfg.collide = parse_collide_kinds("all");
    if (seed == 4) cfg.clearance = 0.01f, cfg.stem_cluster = 40;
    rebuild_mbvt(reused, s, lib, cfg);
    CHECK(same_tree(reused, build_mbvt(s, lib, cfg)));
  }
}

TEST_CASE("every organ's OBB is make_obb's, whether or not the plants' organs follow one another") {
  // A grown stand's plants hold consecutive organ ranges (each plant's OBBs are then made with
  // its clusters); with two plants' records swapped, the ranges no longer follow the plant order
  // (all OBBs are made first). Either way each OBB is make_obb's, bit for bit.
  for (std::uint64_t seed : {4, 7}) {
    Stand s = seed % 2 ? random_stand(seed) : row_stand(seed);
    for (int swapped = 0; swapped < 2; ++swapped) {
      if (swapped) {
        std::swap(s.plants[0], s.plants[1]);
        for (OrganRecord& r : s.organs) r.plant = r.plant == 0 ? 1 : r.plant == 1 ? 0 : r.plant;
      }
      PrototypeLibrary lib;
      MbvtConfig cfg;
      cfg.clearance = swapped ? 0.002f : 0.0f;
      const Mbvt m = build_mbvt(s, lib, cfg);
      REQUIRE(m.obbs.size() == s.organ_count());
      std::size_t differ = 0;
      for (std::size_t i = 0; i < s.organ_count(); ++i) {
        const OrganRecord& r = s.organs[i];
        const Obb want = make_obb(s.transforms[i], lib.get(r).box, cfg.clearance);
        differ += std::memcmp(&want, &m.obbs[i], sizeof want) != 0;
      }
      INFO("seed " << seed << " swapped " << swapped);
      CHECK(differ == 0);
    }
  }
}

TEST_CASE(
    "curved leaflets: every vertex lies in its OBB, its cluster's LCD boxes and its plant's bounds, at every "
    "level of detail") {
  std::set<int> shapes;
  for (int lod = 1; lod <= 4; ++lod) {
    const Stand s = curved_stand(static_cast<std::uint64_t>(lod), lod);
    PrototypeLibrary lib;
    MbvtConfig cfg;
    cfg.collide = parse_collide_kinds("all");
    const Mbvt m = build_mbvt(s, lib, cfg);
    OrganMesh mesh;
    for (const Cluster& c : m.clusters)
      for (std::uint32_t n = c.first_node; n < c.first_node + c.node_count; ++n)
        for (std::uint32_t k = m.nodes[n].first; k < m.nodes[n].first + m.nodes[n].count; ++k) {
          organ_mesh(s, m.cluster_organs[k], lib, mesh, true);
          for (const Vec3f& v : mesh.positions) {
            Lcd point;
            point.ax = m.nodes[n].box.ax, point.ay = m.nodes[n].box.ay;
            lcd_add(point, v);
            for (int d = 0; d < 3; ++d) {
              CHECK(point.lo[d] >= m.nodes[n].box.lo[d]);
              CHECK(point.hi[d] <= m.nodes[n].box.hi[d]);
            }
          }
        }
    for (std::size_t id = 0; id < s.organ_count(); ++id) {
      if (s.organs[id].shape) shapes.insert(s.organs[id].shape);
      organ_mesh(s, id, lib, mesh, true);
      const Obb& o = m.obbs[id];
      const PlantBound& pb = m.plants[static_cast<std::size_t>(s.organs[id].plant)];
      for (const Vec3f& v : mesh.positions) {
        const Vec3f d = v - o.centre;
        for (int k = 0; k < 3; ++k) CHECK(std::fabs(dot(d, o.axis[k])) <= o.half[k]);
        CHECK(std::hypot(v.x, v.y) <= pb.radius);
        CHECK(v.z >= pb.zlo);
        CHECK(v.z <= pb.zhi);
      }
    }
  }
  MESSAGE(shapes.size() << " leaflet shapes bounded");
  CHECK(shapes.size() > 60);  // the stands curve their leaflets in many ways
}
