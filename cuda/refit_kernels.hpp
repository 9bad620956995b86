#pragma once
/// Fitting the tree's boxes on the device: every box at a build (the tree's shape comes from the
/// host), and after organs turn (resolution rounds) the moved organs' OBBs from their
/// transforms, then the LCD boxes of the clusters of their plants (axes kept), then those
/// plants' bounds. The same CANOPY_HD functions as the host's fit_mbvt and refit_mbvt
/// (geometry/obb.hpp, collision/mbvt_fit.hpp), so the same bits.
#include "collision/mbvt.hpp"

#include <cstdint>

namespace canopy::cuda {

/// Writable views of the device tree.
struct TreeView {
  const Affine3f* transforms;
  const OrganRecord* organs;
  const Box3f* boxes;  // prototype boxes, by mesh_slot(prototype, lod, shape)
  const std::uint32_t* cluster_organs;
  Cluster* clusters;  // their axis-aligned boxes are refitted with the plant bounds
  Obb* obbs;
  LcdNode* nodes;
  PlantBound* plants;
  float* max_radius;  // the largest plant radius fitted so far (never lowered by a refit)
};

/// OBBs of organs[0, n), or of organs 0 to n - 1 when `organs` is null.
void launch_refit_organs(const TreeView& v, const std::uint32_t* organs, std::uint32_t n, float clearance);
/// LCD node boxes of clusters[0, n), axes kept (a refit).
void launch_refit_clusters(const TreeView& v, const std::uint32_t* clusters, std::uint32_t n);
/// Every cluster's axis and node boxes (a build): `clusters` clusters, `nodes` nodes.
void launch_fit_clusters(const TreeView& v, std::uint32_t clusters, std::uint32_t nodes);
/// Bounds of plants[0, n) (or 0 to n - 1), raising *max_radius to the largest.
void launch_refit_plants(const TreeView& v, const std::uint32_t* plants, std::uint32_t n);

}  // namespace canopy::cuda
