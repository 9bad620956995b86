#pragma once
/// The stand and its MBVT on the device, kept between detection rounds: uploaded once by
/// `load`, refit on the device by `refit` after organs turned (only the moved organs' transforms
/// travel), with the plant bounds brought back for the host's grid broad phase.
#include "collision/mbvt.hpp"
#include "cuda/detect_kernels.hpp"
#include "cuda/device_buffer.hpp"
#include "cuda/refit_kernels.hpp"
#include "geometry/prototype.hpp"
#include "geometry/stand.hpp"

#include <vector>

namespace canopy::cuda {

class StandOnDevice {
 public:
  /// Uploads the stand, its tree and the prototype meshes (stored once).
  void load(const Stand& s, const Mbvt& m, PrototypeLibrary& lib);
  /// After organs `moved` turned: their transforms up, their OBBs, their plants' cluster boxes
  /// and plant bounds refit on the device; the new bounds of those plants written into m.plants.
  void refit(const Stand& s, Mbvt& m, const std::vector<std::uint32_t>& moved);
  const StandView& view() const { return view_; }
  /// Bytes held on the device by the stand and its tree.
  std::size_t bytes() const { return bytes_; }

 private:
  DeviceBuffer<Affine3f> transforms_;
  DeviceBuffer<OrganRecord> organs_;
  DeviceBuffer<Obb> obbs_;
  DeviceBuffer<std::uint32_t> cluster_organs_;
  DeviceBuffer<Cluster> clusters_;
  DeviceBuffer<LcdNode> nodes_;
  DeviceBuffer<PlantBound> plants_;
  DeviceBuffer<Vec3f> positions_;
  DeviceBuffer<std::uint32_t> indices_;
  DeviceBuffer<MeshRef> meshes_;
  DeviceBuffer<Box3f> boxes_;
  DeviceBuffer<std::uint32_t> ids_;
  DeviceBuffer<Affine3f> moved_transforms_;
  StandView view_{};
  TreeView tree_{};
  std::size_t bytes_ = 0;
};

}  // namespace canopy::cuda
