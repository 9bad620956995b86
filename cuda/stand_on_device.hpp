#pragma once
/// The stand and its MBVT on the device, kept between detection rounds: `load` uploads the
/// stand, the tree's shape (built on the host from the stand's structure alone) and the
/// prototype meshes (stored once); `fit` makes every box on the device; `refit` redoes the boxes
/// of organs that turned (only their transforms travel). The plant bounds stay on the device:
/// the plant grid runs there too.
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
  /// Uploads the stand, the shape of its tree `m` (boxes not needed), the flags of plants that
  /// meet themselves, and the prototype meshes.
  void load(const Stand& s, const Mbvt& m, PrototypeLibrary& lib, const std::vector<std::uint8_t>& self) {
    begin_load(s, lib);
    end_load(s, m, self);
  }
  /// The same in two halves, so that the host builds the tree's shape while the stand travels:
  /// begin_load gathers the prototype meshes, sets the stand's own arrays (transforms, organ
  /// records, plant origins) copying on the staging threads and returns; end_load waits for the
  /// copies and uploads the rest. `s` must stay as it is until end_load or abandon_load.
  void begin_load(const Stand& s, PrototypeLibrary& lib);
  void end_load(const Stand& s, const Mbvt& m, const std::vector<std::uint8_t>& self);
  /// Waits for begin_load's copies and forgets them: what fails between the halves calls it
  /// before the stand may go (a copy would read freed memory).
  void abandon_load() noexcept { staging_.drop(); }
  StandOnDevice() = default;
  StandOnDevice(const StandOnDevice&) = delete;
  StandOnDevice& operator=(const StandOnDevice&) = delete;
  /// Copies under way end before the buffers they write are freed.
  ~StandOnDevice() { staging_.drop(); }
  /// The staging blocks allocated from now on, on a thread of their own (a backend starting).
  void reserve_staging() { staging_.reserve_in_background(); }
  /// Every OBB, cluster axis, LCD box and plant bound, on the device (no copy).
  void fit(float clearance);
  /// After organs `moved` turned: their transforms up, their OBBs, their plants' cluster boxes
  /// and plant bounds refit on the device.
  void refit(const Stand& s, const Mbvt& m, const std::vector<std::uint32_t>& moved);
  /// The largest plant radius fitted (one float down).
  float max_radius() const;
  /// The clearance the organs' OBBs were fitted with: at 0 they are, bit for bit, the host's
  /// make_obb(transform, prototype box, 0) (the same CANOPY_HD function, no fused operations),
  /// which resolution's attempts on the device then read instead of an uploaded copy.
  float obb_clearance() const { return obb_clearance_; }
  const StandView& view() const { return view_; }
  const std::uint8_t* self() const { return self_.get(); }
  std::uint32_t plants() const { return static_cast<std::uint32_t>(plants_.size()); }
  std::size_t organs() const { return organs_.size(); }
  /// The least origin coordinates (the grid's corner) and their spans.
  double x0() const { return x0_; }
  double y0() const { return y0_; }
  double span() const { return span_; }
  /// Bytes held on the device by the stand and its tree.
  std::size_t bytes() const { return bytes_; }

 private:
  PinnedUpload staging_;
  DeviceBuffer<Affine3f> transforms_;
  DeviceBuffer<OrganRecord> organs_;
  DeviceBuffer<Obb> obbs_;
  DeviceBuffer<std::uint32_t> cluster_organs_;
  DeviceBuffer<Cluster> clusters_;
  DeviceBuffer<LcdNode> nodes_;
  DeviceBuffer<PlantBound> plants_;
  DeviceBuffer<PlantOrigin> origins_;
  DeviceBuffer<std::uint8_t> self_;
  DeviceBuffer<float> max_radius_;
  DeviceBuffer<Vec3f> positions_;
  DeviceBuffer<std::uint32_t> indices_;
  DeviceBuffer<MeshRef> meshes_;
  DeviceBuffer<Box3f> boxes_;
  DeviceBuffer<std::uint32_t> ids_, dirty_clusters_, dirty_plants_;
  DeviceBuffer<Affine3f> moved_transforms_;
  std::vector<PlantOrigin> host_origins_;  // the origins' source while they travel
  std::vector<MeshRef> mesh_refs_;         // the meshes gathered by begin_load, per slot
  std::vector<Box3f> mesh_boxes_;
  std::vector<Vec3f> mesh_positions_;
  std::vector<std::uint32_t> mesh_indices_;
  StandView view_{};
  TreeView tree_{};
  double x0_ = 0, y0_ = 0, span_ = 0;
  float obb_clearance_ = 0;
  std::size_t bytes_ = 0;
};

}  // namespace canopy::cuda
