#pragma once
/// Refitting the MBVT's boxes from organ OBBs, shared by the host (build_mbvt, refit_mbvt) and
/// the CUDA backend's refit kernels (CANOPY_HD): one implementation, the same bits on both.
#include "collision/contacts.hpp"
#include "collision/mbvt.hpp"
#include "geometry/hd.hpp"

namespace canopy {

/// The LCD axis of cluster c (horizontal, from its first organ towards the mean of its organs'
/// centres), written into every node of the cluster; fixed from then on (refits keep it).
CANOPY_HD inline void fit_cluster_axis(LcdNode* nodes, const Obb* obbs, const std::uint32_t* cluster_organs,
                                       const Cluster& c) {
  float mx = 0, my = 0;
  for (std::uint32_t k = c.first; k < c.first + c.count; ++k)
    mx += obbs[cluster_organs[k]].centre.x, my += obbs[cluster_organs[k]].centre.y;
  mx = mx / static_cast<float>(c.count) - obbs[cluster_organs[c.first]].centre.x;
  my = my / static_cast<float>(c.count) - obbs[cluster_organs[c.first]].centre.y;
  const float len = sqrtf(mx * mx + my * my);
  const float ax = len > 1e-6f ? mx / len : 1.0f, ay = len > 1e-6f ? my / len : 0.0f;
  for (std::uint32_t n = c.first_node; n < c.first_node + c.node_count; ++n)
    nodes[n].box.ax = ax, nodes[n].box.ay = ay;
}

/// Whether organs cluster_organs[first, first + count) hold a pair that is not adjacent (so a
/// contact among them is possible): the host's shape build (clusters above kMaskOrgans organs,
/// plants) and the CUDA cluster-pairs kernel.
CANOPY_HD inline bool organs_hold_free_pair(const OrganRecord* organs, const std::uint32_t* cluster_organs,
                                            std::uint32_t first, std::uint32_t count) {
  for (std::uint32_t i = first; i < first + count; ++i)
    for (std::uint32_t j = i + 1; j < first + count; ++j) {
      const auto a = static_cast<std::int32_t>(cluster_organs[i]),
                 b = static_cast<std::int32_t>(cluster_organs[j]);
      if (!adjacent(organs[a], a, organs[b], b)) return true;
    }
  return false;
}

/// The offset that carries plant b's frame into plant a's, from their origins (double, as the
/// stand keeps them), rounded once to float: the same bits on both backends.
CANOPY_HD inline Vec3f origin_offset(double ax, double ay, double bx, double by) {
  return {static_cast<float>(bx - ax), static_cast<float>(by - ay), 0.0f};
}

/// Whether two plants' bounds (vertical cylinders about origins dx, dy apart) overlap.
CANOPY_HD inline bool plant_bounds_meet(const PlantBound& a, const PlantBound& b, double dx, double dy) {
  if (a.zlo > a.zhi || b.zlo > b.zhi) return false;
  if (a.zlo > b.zhi || b.zlo > a.zhi) return false;
  const double r = static_cast<double>(a.radius) + static_cast<double>(b.radius);
  return dx * dx + dy * dy <= r * r;
}

/// The box of a leaf node of a cluster's tree (its axis already set) from its organs' OBBs.
CANOPY_HD inline void fit_leaf_node(LcdNode& node, const Obb* obbs, const std::uint32_t* cluster_organs) {
  const float ax = node.box.ax, ay = node.box.ay;
  node.box = Lcd{};
  node.box.ax = ax, node.box.ay = ay;
  for (std::uint32_t k = node.first; k < node.first + node.count; ++k)
    lcd_add(node.box, obbs[cluster_organs[k]]);
  lcd_inflate(node.box, 0);  // rounding slack of the projection
}

/// The box of inner node n from its children's (children come before parents, and share the
/// axis: an exact merge).
CANOPY_HD inline void fit_inner_node(LcdNode* nodes, std::uint32_t n) {
  LcdNode& node = nodes[n];
  const float ax = node.box.ax, ay = node.box.ay;
  node.box = Lcd{};
  node.box.ax = ax, node.box.ay = ay;
  lcd_merge(node.box, nodes[node.left].box);
  lcd_merge(node.box, nodes[node.right].box);
}

/// The inner nodes of cluster c, bottom-up, once its leaf nodes are fitted.
CANOPY_HD inline void fit_inner_nodes(LcdNode* nodes, const Cluster& c) {
  for (std::uint32_t n = c.first_node; n < c.first_node + c.node_count; ++n)
    if (nodes[n].left >= 0) fit_inner_node(nodes, n);
}

/// Boxes of every node of cluster c from its organs' OBBs, bottom-up (children before parents).
CANOPY_HD inline void fit_cluster_nodes(LcdNode* nodes, const Obb* obbs, const std::uint32_t* cluster_organs,
                                        const Cluster& c) {
  for (std::uint32_t n = c.first_node; n < c.first_node + c.node_count; ++n)
    if (nodes[n].left < 0) fit_leaf_node(nodes[n], obbs, cluster_organs);
  fit_inner_nodes(nodes, c);
}

/// An axis-aligned box around LCD box l (its four horizontal corners, its vertical extent),
/// widened by 16 times the bounds' relative slack: far above the rounding of the corners and of
/// lcd_overlap's arithmetic, so a pre-test on these boxes never rejects a pair of LCD boxes that
/// lcd_overlap accepts (tests/collision/test_bounds.cpp). Empty (lo > hi) for an empty l.
CANOPY_HD inline Box3f lcd_aabb(const Lcd& l) {
  Box3f b{{3e38f, 3e38f, 3e38f}, {-3e38f, -3e38f, -3e38f}};
  if (lcd_empty(l)) return b;
  for (int i = 0; i < 4; ++i) {
    float x, y;
    lcd_corner(l, i, x, y);
    b.lo.x = min_f(b.lo.x, x), b.hi.x = max_f(b.hi.x, x);
    b.lo.y = min_f(b.lo.y, y), b.hi.y = max_f(b.hi.y, y);
  }
  const float size =
      fabsf(b.lo.x) + fabsf(b.hi.x) + fabsf(b.lo.y) + fabsf(b.hi.y) + fabsf(l.lo[2]) + fabsf(l.hi[2]);
  const float s = 16 * kBoundRelSlack * size + kBoundAbsSlack;
  b.lo = {b.lo.x - s, b.lo.y - s, l.lo[2] - s};
  b.hi = {b.hi.x + s, b.hi.y + s, l.hi[2] + s};
  return b;
}

/// Whether axis-aligned boxes a and b (b moved by `offset`) meet (closed; empty boxes never do).
CANOPY_HD inline bool boxes_meet(const Box3f& a, const Box3f& b, Vec3f offset) {
  return a.lo.x <= b.hi.x + offset.x && b.lo.x + offset.x <= a.hi.x && a.lo.y <= b.hi.y + offset.y &&
         b.lo.y + offset.y <= a.hi.y && a.lo.z <= b.hi.z + offset.z && b.lo.z + offset.z <= a.hi.z;
}

/// A plant's bound (horizontal radius about its origin, vertical extent, axis-aligned box) from
/// its clusters' roots; each cluster's axis-aligned box on the way.
CANOPY_HD inline void fit_plant_bound(const LcdNode* nodes, Cluster* clusters, PlantBound& pb) {
  float r2 = 0, zlo = 0, zhi = -1;
  bool any = false;
  Box3f box{{3e38f, 3e38f, 3e38f}, {-3e38f, -3e38f, -3e38f}};
  for (std::uint32_t c = pb.first_cluster; c < pb.first_cluster + pb.cluster_count; ++c) {
    const Lcd& l = nodes[clusters[c].root].box;
    const Box3f cb = clusters[c].box = lcd_aabb(l);
    if (lcd_empty(l)) continue;
    box.lo = {min_f(box.lo.x, cb.lo.x), min_f(box.lo.y, cb.lo.y), min_f(box.lo.z, cb.lo.z)};
    box.hi = {max_f(box.hi.x, cb.hi.x), max_f(box.hi.y, cb.hi.y), max_f(box.hi.z, cb.hi.z)};
    for (int i = 0; i < 4; ++i) {
      float x, y;
      lcd_corner(l, i, x, y);
      r2 = max_f(r2, x * x + y * y);
    }
    zlo = any ? min_f(zlo, l.lo[2]) : l.lo[2];
    zhi = any ? max_f(zhi, l.hi[2]) : l.hi[2];
    any = true;
  }
  const float r = sqrtf(r2);
  pb.radius = any ? r + kBoundRelSlack * (r + fabsf(zlo) + fabsf(zhi)) + kBoundAbsSlack : 0;
  pb.zlo = zlo;
  pb.zhi = zhi;
  pb.box = box;
}

}  // namespace canopy
