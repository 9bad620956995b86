#include "cuda/stand_on_device.hpp"

#include "cuda/scatter.hpp"
#include "geometry/organ_mesh.hpp"

#include <algorithm>
#include <stdexcept>

namespace canopy::cuda {

void StandOnDevice::begin_load(const Stand& s, PrototypeLibrary& lib) {
  staging_.drop();  // an earlier load abandoned halfway (its buffers are about to be replaced)
  host_origins_.resize(s.plant_count());
  double x1 = 0, y1 = 0;
  for (std::size_t p = 0; p < s.plant_count(); ++p) {
    host_origins_[p] = {s.plants[p].x, s.plants[p].y};
    x0_ = p ? std::min(x0_, s.plants[p].x) : s.plants[p].x,
    x1 = p ? std::max(x1, s.plants[p].x) : s.plants[p].x;
    y0_ = p ? std::min(y0_, s.plants[p].y) : s.plants[p].y,
    y1 = p ? std::max(y1, s.plants[p].y) : s.plants[p].y;
  }
  span_ = std::max(x1 - x0_, y1 - y0_);
  // The meshes the stand uses, stored once in slot order; made before the copies start, so that
  // nothing between here and end_load throws while they run.
  const std::vector<const PrototypeMesh*> meshes = make_meshes(s, lib);
  mesh_refs_.assign(kMeshSlots, MeshRef{});
  mesh_boxes_.assign(kMeshSlots, Box3f{});
  mesh_positions_.clear();
  mesh_indices_.clear();
  for (std::size_t slot = 0; slot < meshes.size(); ++slot) {
    if (!meshes[slot]) continue;
    const PrototypeMesh& pm = *meshes[slot];
    mesh_refs_[slot] = {
        static_cast<std::uint32_t>(mesh_positions_.size()), static_cast<std::uint32_t>(pm.positions.size()),
        static_cast<std::uint32_t>(mesh_indices_.size()), static_cast<std::uint32_t>(pm.triangle_count())};
    mesh_boxes_[slot] = pm.box;
    mesh_positions_.insert(mesh_positions_.end(), pm.positions.begin(), pm.positions.end());
    mesh_indices_.insert(mesh_indices_.end(), pm.indices.begin(), pm.indices.end());
  }
  transforms_.upload(s.transforms, staging_);
  organs_.upload(s.organs, staging_);
  origins_.upload(host_origins_, staging_);
  obbs_.resize(s.organ_count());
  staging_.start();
}

void StandOnDevice::end_load(const Stand& s, const Mbvt& m, const std::vector<std::uint8_t>& self) {
  staging_.wait();
  // The tree's arrays, queued and copied together (cuda/pinned_upload.hpp).
  cluster_organs_.upload(m.cluster_organs, staging_);
  clusters_.upload(m.clusters, staging_);
  nodes_.upload(m.nodes, staging_);
  plants_.upload(m.plants, staging_);
  staging_.finish();
  self_.upload(self);
  max_radius_.resize(1);
  positions_.upload(mesh_positions_);
  indices_.upload(mesh_indices_);
  meshes_.upload(mesh_refs_);
  boxes_.upload(mesh_boxes_);
  view_ = {transforms_.get(), organs_.get(), obbs_.get(),   cluster_organs_.get(),
           clusters_.get(),   nodes_.get(),  plants_.get(), positions_.get(),
           indices_.get(),    meshes_.get(), origins_.get()};
  tree_ = {transforms_.get(), organs_.get(), boxes_.get(),  cluster_organs_.get(), clusters_.get(),
           obbs_.get(),       nodes_.get(),  plants_.get(), max_radius_.get()};
  bytes_ = s.transforms.size() * sizeof(Affine3f) + s.organs.size() * sizeof(OrganRecord) +
           s.organ_count() * sizeof(Obb) + m.cluster_organs.size() * 4 + m.clusters.size() * sizeof(Cluster) +
           m.nodes.size() * sizeof(LcdNode) +
           m.plants.size() * (sizeof(PlantBound) + sizeof(PlantOrigin) + 1) +
           mesh_positions_.size() * sizeof(Vec3f) + mesh_indices_.size() * 4 +
           mesh_refs_.size() * sizeof(MeshRef) + mesh_boxes_.size() * sizeof(Box3f) + sizeof(float);
}

void StandOnDevice::fit(float clearance) {
  obb_clearance_ = clearance;
  CANOPY_CUDA_CHECK(cudaMemset(max_radius_.get(), 0, sizeof(float)));
  launch_refit_organs(tree_, nullptr, static_cast<std::uint32_t>(obbs_.size()), clearance);
  launch_fit_clusters(tree_, static_cast<std::uint32_t>(clusters_.size()),
                      static_cast<std::uint32_t>(nodes_.size()));
  launch_refit_plants(tree_, nullptr, static_cast<std::uint32_t>(plants_.size()));
}

float StandOnDevice::max_radius() const {
  float r = 0;
  CANOPY_CUDA_CHECK(cudaMemcpy(&r, max_radius_.get(), sizeof r, cudaMemcpyDeviceToHost));
  return r;
}

void StandOnDevice::refit(const Stand& s, const Mbvt& m, const std::vector<std::uint32_t>& moved) {
  if (moved.empty()) return;
  if (m.config.clearance != obb_clearance_)
    throw std::logic_error("refit: not the clearance the boxes were fitted with");
  // The moved organs' transforms, scattered into place (ids_ keeps the ids for the refit).
  scatter_from_host(transforms_.get(), s.transforms.data(), moved, ids_, moved_transforms_);
  launch_refit_organs(tree_, ids_.get(), static_cast<std::uint32_t>(moved.size()), m.config.clearance);
  // Every cluster of the plants that moved (their LCD boxes keep the axes fixed at the build),
  // then the plants' bounds.
  std::vector<std::uint32_t> plants;
  for (std::uint32_t k : moved) plants.push_back(static_cast<std::uint32_t>(s.organs[k].plant));
  std::sort(plants.begin(), plants.end());
  plants.erase(std::unique(plants.begin(), plants.end()), plants.end());
  std::vector<std::uint32_t> clusters;
  for (std::uint32_t p : plants)
    for (std::uint32_t c = m.plants[p].first_cluster;
         c < m.plants[p].first_cluster + m.plants[p].cluster_count; ++c)
      clusters.push_back(c);
  dirty_clusters_.upload(clusters);
  dirty_plants_.upload(plants);
  launch_refit_clusters(tree_, dirty_clusters_.get(), static_cast<std::uint32_t>(clusters.size()));
  launch_refit_plants(tree_, dirty_plants_.get(), static_cast<std::uint32_t>(plants.size()));
}

}  // namespace canopy::cuda
