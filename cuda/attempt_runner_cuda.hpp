#pragma once
/// Resolution's bulk attempts on the device (collision/attempt_batch.hpp): the batch's tables
/// kept on the device and appended to as the host appends, each call's groups expanded into
/// (group, pair) box tests and exact tests by a warp per pair (cuda/attempt_kernels.hpp). The
/// meshes, organ records and plant origins are the detection's (StandOnDevice), which stay
/// fixed while a stand resolves.
#include "collision/attempt_batch.hpp"
#include "cuda/attempt_kernels.hpp"
#include "cuda/device_buffer.hpp"
#include "cuda/stand_on_device.hpp"

#include <cstdlib>

namespace canopy::cuda {

class CudaAttemptRunner : public AttemptRunner {
 public:
  explicit CudaAttemptRunner(const StandOnDevice& dev);
  ~CudaAttemptRunner() override;
  /// Uploads every box (`all`) or scatters the changed organs' boxes; the transforms are the
  /// device stand's, which the backend's redetect() keeps current.
  void update_organs(const Stand& stand, std::span<const Obb> boxes, std::span<const std::uint32_t> changed, bool all) override;
  void clear() override;
  std::vector<std::uint32_t> touching(const AttemptTables& tables, std::span<const AttemptGroup> groups,
                                      const AttemptSettings& settings) override;

 private:
  /// What the device did so far (printed with CANOPY_BULK_STATS): calls, box and exact tests,
  /// bytes sent, seconds spent in calls.
  struct Stats {
    std::uint64_t calls = 0, groups = 0, box_tests = 0, witness_hits = 0, exact_tests = 0, exact_touches = 0, uploaded_bytes = 0;
    double seconds = 0, upload_s = 0, box_s = 0, exact_s = 0;
  };
  /// Sends the entries of `host` appended since the last call (all of them after a clear).
  template <typename T, typename A>
  void sync(DeviceBuffer<T>& device, const std::vector<T, A>& host, std::size_t& sent) {
    device.grow_keeping(host.size(), sent);
    device.upload_at(sent, host.data() + sent, host.size() - sent);
    sent = host.size();
  }

  const StandOnDevice& dev_;
  const bool report_ = std::getenv("CANOPY_BULK_STATS") != nullptr;  // print Stats when done
  DeviceBuffer<Obb> boxes_, staged_boxes_;
  DeviceBuffer<std::uint32_t> staged_ids_;
  DeviceBuffer<std::int32_t> moving_;
  DeviceBuffer<KeepEntry> keep_;
  DeviceBuffer<PairEntry> pairs_;
  DeviceBuffer<std::uint32_t> witness_;  // per pair; the exact tests bring it up to date on the device
  DeviceBuffer<Vec3d> axes_;
  std::size_t moving_sent_ = 0, keep_sent_ = 0, pairs_sent_ = 0, witness_sent_ = 0, axes_sent_ = 0;
  DeviceBuffer<AttemptGroup> groups_;
  DeviceBuffer<std::uint32_t> task_first_, touch_;
  DeviceBuffer<ExactAttempt> exact_;
  DeviceBuffer<Counters> counters_;
  Stats stats_;
};

}  // namespace canopy::cuda
