#include "cuda/stand_on_device.hpp"

#include <algorithm>

namespace canopy::cuda {

void StandOnDevice::load(const Stand& s, const Mbvt& m, PrototypeLibrary& lib) {
  std::vector<MeshRef> meshes(4 * (kMaxLod + 1));
  std::vector<Box3f> boxes(4 * (kMaxLod + 1));
  std::vector<Vec3f> positions;
  std::vector<std::uint32_t> indices;
  for (const OrganRecord& r : s.organs) {
    const std::size_t slot = static_cast<std::size_t>(r.prototype) * (kMaxLod + 1) + r.lod;
    MeshRef& ref = meshes[slot];
    if (ref.vertex_count) continue;
    const PrototypeMesh& pm = lib.get(r.prototype, r.lod);
    ref = {static_cast<std::uint32_t>(positions.size()), static_cast<std::uint32_t>(pm.positions.size()),
           static_cast<std::uint32_t>(indices.size()), static_cast<std::uint32_t>(pm.triangle_count())};
    boxes[slot] = pm.box;
    positions.insert(positions.end(), pm.positions.begin(), pm.positions.end());
    indices.insert(indices.end(), pm.indices.begin(), pm.indices.end());
  }
  transforms_.upload(s.transforms);
  organs_.upload(s.organs);
  obbs_.upload(m.obbs);
  cluster_organs_.upload(m.cluster_organs);
  clusters_.upload(m.clusters);
  nodes_.upload(m.nodes);
  plants_.upload(m.plants);
  positions_.upload(positions);
  indices_.upload(indices);
  meshes_.upload(meshes);
  boxes_.upload(boxes);
  view_ = {transforms_.get(), organs_.get(), obbs_.get(), cluster_organs_.get(), clusters_.get(), nodes_.get(),
           plants_.get(), positions_.get(), indices_.get(), meshes_.get()};
  tree_ = {transforms_.get(), organs_.get(), boxes_.get(), cluster_organs_.get(), clusters_.get(), obbs_.get(), nodes_.get(),
           plants_.get()};
  bytes_ = s.transforms.size() * sizeof(Affine3f) + s.organs.size() * sizeof(OrganRecord) + m.obbs.size() * sizeof(Obb) +
           m.cluster_organs.size() * 4 + m.clusters.size() * sizeof(Cluster) + m.nodes.size() * sizeof(LcdNode) +
           m.plants.size() * sizeof(PlantBound) + positions.size() * sizeof(Vec3f) + indices.size() * 4 +
           meshes.size() * sizeof(MeshRef) + boxes.size() * sizeof(Box3f);
}

void StandOnDevice::refit(const Stand& s, Mbvt& m, const std::vector<std::uint32_t>& moved) {
  if (moved.empty()) return;
  // The moved organs' transforms, scattered into place.
  std::vector<Affine3f> t;
  t.reserve(moved.size());
  for (std::uint32_t k : moved) t.push_back(s.transforms[k]);
  ids_.upload(moved);
  moved_transforms_.upload(t);
  launch_scatter(transforms_.get(), moved_transforms_.get(), ids_.get(), static_cast<std::uint32_t>(moved.size()),
                 sizeof(Affine3f) / 4);
  launch_refit_organs(tree_, ids_.get(), static_cast<std::uint32_t>(moved.size()), m.config.clearance);
  // Every cluster of the plants that moved (their LCD boxes share axes fixed at build), then the
  // plants' bounds.
  std::vector<std::uint32_t> plants;
  for (std::uint32_t k : moved) plants.push_back(static_cast<std::uint32_t>(s.organs[k].plant));
  std::sort(plants.begin(), plants.end());
  plants.erase(std::unique(plants.begin(), plants.end()), plants.end());
  std::vector<std::uint32_t> clusters;
  for (std::uint32_t p : plants)
    for (std::uint32_t c = m.plants[p].first_cluster; c < m.plants[p].first_cluster + m.plants[p].cluster_count; ++c)
      clusters.push_back(c);
  DeviceBuffer<std::uint32_t> cl, pl;
  cl.upload(clusters);
  pl.upload(plants);
  launch_refit_clusters(tree_, cl.get(), static_cast<std::uint32_t>(clusters.size()));
  launch_refit_plants(tree_, pl.get(), static_cast<std::uint32_t>(plants.size()));
  CANOPY_CUDA_CHECK(cudaDeviceSynchronize());
  // The bounds back to the host for the grid (a few bytes per plant).
  const std::vector<PlantBound> all = plants_.download(m.plants.size());
  for (std::uint32_t p : plants) {
    m.plants[p] = all[p];
    m.max_radius = std::max(m.max_radius, all[p].radius);
  }
}

}  // namespace canopy::cuda
