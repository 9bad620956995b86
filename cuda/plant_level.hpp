#pragma once
/// The plant level on the device: plants sorted into grid cells (again only when the cell size
/// changes: origins never move), pairs whose bounds meet found by the grid kernel, then sorted
/// as the CPU sorts them (p, q) and made into the work list of the later stages.
#include "collision/backend.hpp"
#include "cuda/detect_kernels.hpp"
#include "cuda/device_buffer.hpp"
#include "cuda/event_timer.hpp"
#include "cuda/keys.hpp"
#include "cuda/stand_on_device.hpp"

#include <cstdint>
#include <optional>
#include <vector>

namespace canopy::cuda {

class PlantLevel {
 public:
  /// The plant pairs of `dev` (keys pair_key(p, q), p <= q; only pairs with an active plant when
  /// the request names some) into `work` on the device and returned on the host; `count` gets
  /// the level's numbers. Under a memory budget (`tight`) only the work list stays allocated.
  std::vector<std::uint64_t> work(const StandOnDevice& dev, const DetectRequest& req, bool tight,
                                  KeyOps& keys, DeviceBuffer<Counters>& counters, EventTimer& timer,
                                  std::optional<LevelCount>& count, DeviceBuffer<WorkItem>& work);
  /// A new stand: the plants are sorted into cells again.
  void reset() { sorted_cell_ = 0; }
  /// Device bytes held between calls besides the work list.
  std::size_t bytes() const { return active_.size(); }

 private:
  DeviceBuffer<std::uint64_t> cells_, sorted_cells_, pair_keys_, work_keys_;
  DeviceBuffer<std::uint32_t> members_, sorted_members_;
  DeviceBuffer<std::uint8_t> active_;
  PinnedBuffer<std::uint64_t> staged_keys_;
  double sorted_cell_ = 0;  // the cell size the plants in sorted_cells_ were sorted for (0: none)
};

}  // namespace canopy::cuda
