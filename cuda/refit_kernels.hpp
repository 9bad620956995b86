#pragma once
/// Refit on the device after organs turn (resolution rounds): the moved organs' OBBs from their
/// transforms, then the LCD boxes of the clusters of their plants, then those plants' bounds. The
/// same CANOPY_HD functions as the host's refit_mbvt (geometry/obb.hpp, collision/mbvt_fit.hpp).
#include "collision/mbvt.hpp"

#include <cstdint>

namespace canopy::cuda {

/// Writable views of the device tree.
struct TreeView {
  const Affine3f* transforms;
  const OrganRecord* organs;
  const Box3f* boxes;  // prototype boxes, by prototype * (kMaxLod + 1) + lod
  const std::uint32_t* cluster_organs;
  const Cluster* clusters;
  Obb* obbs;
  LcdNode* nodes;
  PlantBound* plants;
};

void launch_refit_organs(const TreeView& v, const std::uint32_t* organs, std::uint32_t n, float clearance);
void launch_refit_clusters(const TreeView& v, const std::uint32_t* clusters, std::uint32_t n);
void launch_refit_plants(const TreeView& v, const std::uint32_t* plants, std::uint32_t n);

}  // namespace canopy::cuda
