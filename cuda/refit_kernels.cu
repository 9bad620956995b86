// Device refit kernels: one thread per moved organ, per dirty cluster, per dirty plant.
#include "collision/mbvt_fit.hpp"
#include "cuda/check.hpp"
#include "cuda/refit_kernels.hpp"
#include "geometry/obb.hpp"

namespace canopy::cuda {
namespace {

constexpr int kThreads = 128;
unsigned blocks(std::uint32_t n) { return (n + kThreads - 1) / kThreads; }

__global__ void refit_organs_kernel(TreeView v, const std::uint32_t* organs, std::uint32_t n,
                                    float clearance) {
  const std::uint32_t k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= n) return;
  const std::uint32_t id = organs ? organs[k] : k;
  const OrganRecord r = v.organs[id];
  v.obbs[id] = make_obb(v.transforms[id], v.boxes[mesh_slot(r.prototype, r.lod, r.shape)], clearance);
}

__global__ void refit_clusters_kernel(TreeView v, const std::uint32_t* clusters, std::uint32_t n) {
  const std::uint32_t k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= n) return;
  fit_cluster_nodes(v.nodes, v.obbs, v.cluster_organs, v.clusters[clusters[k]]);
}

// A build fits every cluster in three launches, for more threads than one per cluster: axes
// (per cluster), leaf nodes (per node), inner nodes (per cluster, bottom-up merges).
__global__ void fit_axes_kernel(TreeView v, std::uint32_t n) {
  const std::uint32_t k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k < n) fit_cluster_axis(v.nodes, v.obbs, v.cluster_organs, v.clusters[k]);
}

__global__ void fit_leaf_nodes_kernel(TreeView v, std::uint32_t n) {
  const std::uint32_t k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k < n && v.nodes[k].left < 0) fit_leaf_node(v.nodes[k], v.obbs, v.cluster_organs);
}

__global__ void fit_inner_nodes_kernel(TreeView v, std::uint32_t n) {
  const std::uint32_t k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k < n) fit_inner_nodes(v.nodes, v.clusters[k]);
}

__global__ void refit_plants_kernel(TreeView v, const std::uint32_t* plants, std::uint32_t n) {
  const std::uint32_t k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= n) return;
  PlantBound& pb = v.plants[plants ? plants[k] : k];
  fit_plant_bound(v.nodes, v.clusters, pb);
  // Radii are not negative, so their bits order as integers do.
  atomicMax(reinterpret_cast<int*>(v.max_radius), __float_as_int(pb.radius));
}

}  // namespace

void launch_refit_organs(const TreeView& v, const std::uint32_t* organs, std::uint32_t n, float clearance) {
  if (!n) return;
  refit_organs_kernel<<<blocks(n), kThreads>>>(v, organs, n, clearance);
  CANOPY_CUDA_CHECK_LAUNCH("refit_organs_kernel");
}

void launch_refit_clusters(const TreeView& v, const std::uint32_t* clusters, std::uint32_t n) {
  if (!n) return;
  refit_clusters_kernel<<<blocks(n), kThreads>>>(v, clusters, n);
  CANOPY_CUDA_CHECK_LAUNCH("refit_clusters_kernel");
}

void launch_fit_clusters(const TreeView& v, std::uint32_t clusters, std::uint32_t nodes) {
  if (!clusters) return;
  fit_axes_kernel<<<blocks(clusters), kThreads>>>(v, clusters);
  CANOPY_CUDA_CHECK_LAUNCH("fit_axes_kernel");
  fit_leaf_nodes_kernel<<<blocks(nodes), kThreads>>>(v, nodes);
  CANOPY_CUDA_CHECK_LAUNCH("fit_leaf_nodes_kernel");
  fit_inner_nodes_kernel<<<blocks(clusters), kThreads>>>(v, clusters);
  CANOPY_CUDA_CHECK_LAUNCH("fit_inner_nodes_kernel");
}

void launch_refit_plants(const TreeView& v, const std::uint32_t* plants, std::uint32_t n) {
  if (!n) return;
  refit_plants_kernel<<<blocks(n), kThreads>>>(v, plants, n);
  CANOPY_CUDA_CHECK_LAUNCH("refit_plants_kernel");
}

}  // namespace canopy::cuda
