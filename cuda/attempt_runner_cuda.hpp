#pragma once
/// Resolution's bulk attempts on the device (resolution/attempt_batch.hpp): the batch's tables
/// kept on the device and appended to as the host appends, each call's groups expanded into
/// (group, pair) box tests and exact tests by a warp per pair (cuda/attempt_kernels.hpp). The
/// meshes, organ records and plant origins are the detection's (StandOnDevice), which stay
/// fixed while a stand resolves.
#include "resolution/attempt_batch.hpp"
#include "cuda/attempt_kernels.hpp"
#include "cuda/busy_timeline.hpp"
#include "cuda/device_buffer.hpp"
#include "cuda/stand_on_device.hpp"

#include <array>
#include <cstddef>
#include <memory>

namespace canopy::cuda {

class CudaAttemptRunner : public AttemptRunner {
 public:
  /// Lanes a runner offers (each made at its first call: a stream and its tables).
  static constexpr std::size_t kLanes = 8;
  explicit CudaAttemptRunner(const StandOnDevice& dev);
  ~CudaAttemptRunner() override;
  /// Where the device stand's OBBs were fitted without a clearance, reads those (the same bits
  /// as `boxes`, kept current by the backend's redetect()); otherwise uploads every box (`all`)
  /// or scatters the changed organs' boxes. The transforms are the device stand's.
  void update_organs(const Stand& stand, std::span<const Obb> boxes, std::span<const std::uint32_t> changed,
                     bool all) override;
  std::size_t lanes() const override { return kLanes; }
  std::string hardware() const override { return "device"; }
  void clear(std::size_t lane) override;
  std::vector<std::uint32_t> touching(std::size_t lane, const AttemptTables& tables,
                                      std::span<const AttemptGroup> groups,
                                      const AttemptSettings& settings) override;
  /// On: from the next call, an event pair around every kernel of every lane (a timeline against
  /// an origin event recorded now) and the exact tests' touches read back (a copy per call).
  void keep_statistics(bool on) override;
  /// The counts of every lane and of update_organs, and the kernels' timeline where kept; then
  /// every count and the timeline start again.
  AttemptStats take_statistics() override;

 private:
  /// What the device did since the last take_statistics: calls, box and exact tests, bytes
  /// sent, seconds spent in calls (summed over lanes, which overlap): handing over the uploads (a
  /// pageable copy returns once the driver holds the bytes), then until the box kernel's count is
  /// back, then until the answers are.
  struct Stats {
    std::uint64_t calls = 0, groups = 0, box_tests = 0, witness_hits = 0, exact_tests = 0, exact_touches = 0,
                  uploaded_bytes = 0;
    double seconds = 0, upload_s = 0, box_s = 0, exact_s = 0;
    void add(const Stats& o);
  };
  /// A lane's stream and its batch's tables on the device, appended to as the host appends.
  struct Lane {
    Lane();
    Stream stream;  // first: the buffers below are allocated and freed in its order
    StreamBuffer<std::int32_t> moving{stream.get()};
    StreamBuffer<KeepEntry> keep{stream.get()};
    StreamBuffer<PairEntry> pairs{stream.get()};
    StreamBuffer<std::uint32_t> witness{
        stream.get()};  // per pair; the exact tests bring it up to date on the device
    StreamBuffer<Vec3d> axes{stream.get()};
    std::size_t moving_sent = 0, keep_sent = 0, pairs_sent = 0, witness_sent = 0, axes_sent = 0;
    StreamBuffer<AttemptGroup> groups{stream.get()};
    StreamBuffer<std::uint32_t> task_first{stream.get()}, touch{stream.get()};
    StreamBuffer<ExactAttempt> exact{stream.get()};
    StreamBuffer<Counters> counters{stream.get()};
    Stats stats;
    BusyTimeline busy;  // with keep_statistics: when the device had this lane's kernels
    /// Sends `bytes` from `from` (pageable host memory) to device address `to` in the stream's
    /// order: the driver copies them into its own page-locked buffers before returning, as fast
    /// as a copy into page-locked memory of the lane's own was (which had to grow, at 1.7 GB/s,
    /// in the first calls of every resolution), and the copy engine sends them from there.
    void put(void* to, const void* from, std::size_t bytes);
    /// Sends the entries of `host` appended since the last call (all of them after a clear).
    template <typename T, typename A>
    void sync(StreamBuffer<T>& device, const std::vector<T, A>& host, std::size_t& sent) {
      device.grow_keeping(host.size(), sent);
      put(device.get() + sent, host.data() + sent, (host.size() - sent) * sizeof(T));
      sent = host.size();
    }
  };
  Lane& lane(std::size_t i);

  const StandOnDevice& dev_;
  bool detail_ = false;  // keep_statistics(true): the timeline and the exact tests' touches
  DeviceBuffer<Obb> boxes_, staged_boxes_;  // a copy of the host's boxes, where the device's differ
  bool device_boxes_ = false;               // reading the device stand's own OBBs
  DeviceBuffer<std::uint32_t> staged_ids_;
  std::array<std::unique_ptr<Lane>, kLanes> lanes_;  // slot i touched only by lane i's thread
  Stats stats_;                                      // of update_organs
  cudaEvent_t origin_{};  // recorded by keep_statistics(true), before every lane's timed work
  cudaMemPool_t pool_{};  // the device's default pool, which the lanes' StreamBuffers draw on
  int device_ = 0;        // the backend's device, made current on every lane's thread
};

}  // namespace canopy::cuda
