#pragma once
/// Items of a host array that changed, sent to the device array that mirrors it: gathered on the
/// host, sent with their ids, scattered into place by launch_scatter. The stand's transforms
/// after a resolution round and the turn search's organ boxes travel this way.
#include "cuda/detect_kernels.hpp"
#include "cuda/device_buffer.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace canopy::cuda {

/// device[k] = host[k] for every k in `ids`; `staged_ids` (left holding the ids) and `staged`
/// grow as needed.
template <typename T>
void scatter_from_host(T* device, const T* host, std::span<const std::uint32_t> ids,
                       DeviceBuffer<std::uint32_t>& staged_ids, DeviceBuffer<T>& staged) {
  static_assert(sizeof(T) % sizeof(std::uint32_t) == 0, "scattered items are whole 32-bit words");
  if (ids.empty()) return;
  std::vector<T> items(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) items[i] = host[ids[i]];
  staged_ids.grow(ids.size());
  staged_ids.upload_at(0, ids.data(), ids.size());
  staged.grow(items.size());
  staged.upload_at(0, items.data(), items.size());
  launch_scatter(device, staged.get(), staged_ids.get(), static_cast<std::uint32_t>(ids.size()),
                 sizeof(T) / sizeof(std::uint32_t));
}

}  // namespace canopy::cuda
