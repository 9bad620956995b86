#include "collision/lanes/organ_lanes.hpp"

#include "collision/mbvt.hpp"
#include "collision/organ_blocks.hpp"
#include "geometry/obb.hpp"

namespace canopy {

namespace {

/// Prefix sums of `count(k)` rounded up to whole lanes of 8; returns the lanes needed.
template <typename Count>
std::size_t lay_out(std::vector<std::uint32_t>& first, std::size_t n, Count count) {
  constexpr std::uint32_t w = OrganLanes::kWidth;
  first.resize(n);
  std::uint32_t lanes = 0;
  for (std::size_t k = 0; k < n; ++k) {
    first[k] = lanes;
    lanes += (count(k) + w - 1) / w * w;
  }
  return lanes + w;
}

}  // namespace

void BoxLanes::assign_empty(std::size_t lanes) {
  const Box3f e = empty_box();
  for (std::size_t lane = 0, n = resize_lanes(lanes); lane < n; ++lane) set(lane, e);
}

void LcdLanes::assign_empty(std::size_t lanes) {
  const LcdCentred e = lcd_centred(Lcd{});
  for (std::size_t lane = 0, n = resize_lanes(lanes); lane < n; ++lane) set(lane, e);
}

void lay_out_lanes(OrganLanes& lanes, const Mbvt& m) {
  lanes.organs.assign_empty(
      lay_out(lanes.organ_first, m.clusters.size(), [&](std::size_t c) { return m.clusters[c].count; }));
  lanes.roots.assign(m.clusters.size(), lcd_centred(Lcd{}));
  lanes.pass.assign(m.clusters.size(), PassCluster{});
  const std::size_t cluster_lanes =
      lay_out(lanes.cluster_first, m.plants.size(), [&](std::size_t p) { return m.plants[p].cluster_count; });
  lanes.clusters.assign_empty(cluster_lanes);
  lanes.root_lanes.assign_empty(cluster_lanes);
}

void fill_organ_lanes(OrganLanes& lanes, const Mbvt& m, std::uint32_t c) {
  const Cluster& cl = m.clusters[c];
  Box3f around = empty_box();
  for (std::uint32_t k = 0; k < cl.count; ++k) {
    const Box3f b = obb_aabb(m.obbs[m.cluster_organs[cl.first + k]]);
    lanes.organs.set(lanes.organ_first[c] + k, b);
    grow_around(around, b);
  }
  lanes.roots[c] = lcd_centred(m.nodes[cl.root].box);
  PassCluster& pc = lanes.pass[c];
  pc.around = around, pc.first = cl.first, pc.count = cl.count, pc.lane = lanes.organ_first[c];
  pc.has_free = m.cluster_has_free[c];
}

void fill_cluster_lanes(OrganLanes& lanes, const Mbvt& m, std::uint32_t p) {
  const PlantBound& pb = m.plants[p];
  for (std::uint32_t k = 0; k < pb.cluster_count; ++k) {
    lanes.clusters.set(lanes.cluster_first[p] + k, m.clusters[pb.first_cluster + k].box);
    lanes.root_lanes.set(lanes.cluster_first[p] + k, lanes.roots[pb.first_cluster + k]);
    lanes.pass[pb.first_cluster + k].box = m.clusters[pb.first_cluster + k].box;
  }
}

}  // namespace canopy
