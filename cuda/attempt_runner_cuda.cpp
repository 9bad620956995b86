#include "cuda/attempt_runner_cuda.hpp"

#include "cuda/scatter.hpp"
#include "geometry/clock.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <stdexcept>

namespace canopy::cuda {
void CudaAttemptRunner::Stats::add(const Stats& o) {
  calls += o.calls, groups += o.groups, box_tests += o.box_tests, witness_hits += o.witness_hits,
      exact_tests += o.exact_tests;
  exact_touches += o.exact_touches, uploaded_bytes += o.uploaded_bytes;
  seconds += o.seconds, upload_s += o.upload_s, box_s += o.box_s, exact_s += o.exact_s;
}

CudaAttemptRunner::Lane::Lane() {
  counters.grow(1);
  exact.grow(1 << 20);
}

void CudaAttemptRunner::Lane::put(void* to, const void* from, std::size_t bytes) {
  if (bytes) CANOPY_CUDA_CHECK(cudaMemcpyAsync(to, from, bytes, cudaMemcpyHostToDevice, stream.get()));
}

CudaAttemptRunner::CudaAttemptRunner(const StandOnDevice& dev) : dev_(dev) {
  // The lanes' buffers come from the device's default pool (StreamBuffer): memory freed there
  // stays in the pool for the next growth instead of going back at every synchronisation, and
  // goes back at the next round's start (update_organs) and when the runner ends.
  int device = 0;
  CANOPY_CUDA_CHECK(cudaGetDevice(&device));
  device_ = device;
  CANOPY_CUDA_CHECK(cudaDeviceGetDefaultMemPool(&pool_, device));
  std::uint64_t keep = std::numeric_limits<std::uint64_t>::max();
  CANOPY_CUDA_CHECK(cudaMemPoolSetAttribute(pool_, cudaMemPoolAttrReleaseThreshold, &keep));
}

CudaAttemptRunner::~CudaAttemptRunner() {
  // The lanes' buffers back to the pool (in their streams' order), then the pool's unused memory
  // back to the device, for whatever runs next.
  for (auto& l : lanes_) l.reset();
  if (cudaDeviceSynchronize() == cudaSuccess) cudaMemPoolTrimTo(pool_, 0);
  if (origin_) cudaEventDestroy(origin_);
}

void CudaAttemptRunner::keep_statistics(bool on) {
  if (on && !origin_) {
    CANOPY_CUDA_CHECK(cudaEventCreate(&origin_));
    CANOPY_CUDA_CHECK(cudaEventRecord(origin_));
    CANOPY_CUDA_CHECK(cudaEventSynchronize(origin_));
  }
  detail_ = on;
}

AttemptStats CudaAttemptRunner::take_statistics() {
  Stats all = stats_;
  AttemptStats out;
  out.hardware = hardware();
  for (const auto& l : lanes_)
    if (l && l->stats.calls) all.add(l->stats), ++out.lanes;
  out.calls = all.calls, out.groups = all.groups, out.box_tests = all.box_tests,
  out.witness_hits = all.witness_hits;
  out.exact_tests = all.exact_tests, out.exact_touches = all.exact_touches,
  out.uploaded_bytes = all.uploaded_bytes;
  out.call_s = all.seconds, out.upload_s = all.upload_s, out.box_s = all.box_s, out.exact_s = all.exact_s;
  // The device's own clock: from the first call's kernels to the last's, and how much of that
  // some lane's kernels were queued or running.
  try {
    CANOPY_CUDA_CHECK(cudaDeviceSynchronize());
    std::vector<std::pair<double, double>> spans;
    for (const auto& l : lanes_)
      if (l && origin_) l->busy.intervals(origin_, spans);
    if (!spans.empty()) {
      double first = spans.front().first, last = spans.front().second;
      for (auto [a, b] : spans) first = std::min(first, a), last = std::max(last, b);
      const auto [covered, summed] = BusyTimeline::covered(spans);
      out.timeline = true;
      out.kernels_span_s = last - first, out.kernels_busy_s = covered, out.kernels_summed_s = summed;
    }
  } catch (const std::exception& e) {
    out.no_timeline = e.what();
  }
  stats_ = {};
  for (auto& l : lanes_)
    if (l) l->stats = {}, l->busy.clear();
  return out;
}

CudaAttemptRunner::Lane& CudaAttemptRunner::lane(std::size_t i) {
  if (i >= kLanes) throw std::out_of_range(fmt::format("bulk attempts: lane {} of {}", i, kLanes));
  // The current device is a thread's own: a lane's thread starts on device 0, and a process
  // given another GPU (a rank under mpirun) would send the lane's streams, buffers and
  // kernels there, to memory of the backend's device.
  CANOPY_CUDA_CHECK(cudaSetDevice(device_));
  if (!lanes_[i]) lanes_[i] = std::make_unique<Lane>();
  return *lanes_[i];
}

void CudaAttemptRunner::update_organs(const Stand& stand, std::span<const Obb> boxes,
                                      std::span<const std::uint32_t> changed, bool all) {
  if (boxes.size() != stand.organ_count())
    throw std::logic_error("bulk attempts: one box per organ expected");
  device_boxes_ = dev_.obb_clearance() == 0 && dev_.organs() == boxes.size();
  if (device_boxes_) {
    boxes_.resize(0);
  } else if (all || boxes_.size() != boxes.size()) {
    if (!all) throw std::logic_error("bulk attempts: organs changed before the runner saw them all");
    boxes_.resize(boxes.size());
    boxes_.upload_at(0, boxes.data(), boxes.size());
    stats_.uploaded_bytes += boxes.size() * sizeof(Obb);
  } else {
    scatter_from_host(boxes_.get(), boxes.data(), changed, staged_ids_, staged_boxes_);
    stats_.uploaded_bytes += changed.size() * (sizeof(Obb) + sizeof(std::uint32_t));
  }
  // The lanes' streams do not wait for the default stream, where these boxes and the device
  // stand's transforms (redetect) were written.
  CANOPY_CUDA_CHECK(cudaDeviceSynchronize());
  // What the lanes' tables outgrew last round goes back to the device (the tables they hold stay).
  CANOPY_CUDA_CHECK(cudaMemPoolTrimTo(pool_, 0));
}

void CudaAttemptRunner::clear(std::size_t i) {
  Lane& l = lane(i);
  l.moving_sent = l.keep_sent = l.pairs_sent = l.witness_sent = l.axes_sent = 0;
}

std::vector<std::uint32_t> CudaAttemptRunner::touching(std::size_t i, const AttemptTables& t,
                                                       std::span<const AttemptGroup> groups,
                                                       const AttemptSettings& settings) {
  std::vector<std::uint32_t> out(groups.size(), 0);
  if (groups.empty()) return out;
  Lane& l = lane(i);
  const cudaStream_t stream = l.stream.get();
  const double t0 = now_seconds();
  if (t.moving.size() < l.moving_sent || t.keep.size() < l.keep_sent || t.pairs.size() < l.pairs_sent ||
      t.axes.size() < l.axes_sent || t.witness.size() < l.witness_sent)
    throw std::logic_error("bulk attempts: the tables shrank without a clear()");
  if (t.witness.size() != t.pairs.size())
    throw std::logic_error("bulk attempts: one witness per pair expected");
  const std::size_t bytes = (t.moving.size() - l.moving_sent) * sizeof(std::int32_t) +
                            (t.keep.size() - l.keep_sent) * sizeof(KeepEntry) +
                            (t.pairs.size() - l.pairs_sent) * (sizeof(PairEntry) + sizeof(std::uint32_t)) +
                            (t.axes.size() - l.axes_sent) * sizeof(Vec3d) +
                            groups.size() * sizeof(AttemptGroup) +
                            (groups.size() + 1) * sizeof(std::uint32_t);
  l.stats.uploaded_bytes += bytes;
  l.sync(l.moving, t.moving, l.moving_sent);
  l.sync(l.keep, t.keep, l.keep_sent);
  l.sync(l.pairs, t.pairs, l.pairs_sent);
  l.sync(l.witness, t.witness, l.witness_sent);  // new pairs only: the device keeps its own up to date
  l.sync(l.axes, t.axes, l.axes_sent);
  // Task t of the box kernel: (group g, pair t - first[g]).
  std::vector<std::uint32_t> first(groups.size() + 1, 0);
  std::uint64_t tasks = 0;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    first[g] = static_cast<std::uint32_t>(tasks);
    tasks += groups[g].pair_end - groups[g].pair_first;
  }
  if (tasks > std::numeric_limits<std::uint32_t>::max())
    throw std::length_error(
        fmt::format("bulk attempts: {} pair tests in one call (at most 2^32 - 1)", tasks));
  first[groups.size()] = static_cast<std::uint32_t>(tasks);
  l.groups.grow(groups.size());
  l.put(l.groups.get(), groups.data(), groups.size() * sizeof(AttemptGroup));
  l.task_first.grow(first.size());
  l.put(l.task_first.get(), first.data(), first.size() * sizeof(std::uint32_t));
  l.touch.grow(groups.size());
  CANOPY_CUDA_CHECK(cudaMemsetAsync(l.touch.get(), 0, groups.size() * sizeof(std::uint32_t), stream));
  if (!device_boxes_ && boxes_.size() != dev_.organs())
    throw std::logic_error("bulk attempts: update_organs() not called for this stand");
  const Obb* obbs = device_boxes_ ? dev_.view().obbs : boxes_.get();
  const AttemptTablesView view{l.moving.get(), l.keep.get(), l.pairs.get(),
                               l.axes.get(),   obbs,         l.witness.get()};
  const auto n_groups = static_cast<std::uint32_t>(groups.size()),
             n_tasks = static_cast<std::uint32_t>(tasks);
  // The exact tests are listed with a capacity; a list that overflows is made again, larger.
  const double t1 = now_seconds();  // the uploads queued (they run before the kernels, in the stream's order)
  Counters host{};
  for (;;) {
    if (detail_) l.busy.begin(stream);
    CANOPY_CUDA_CHECK(cudaMemsetAsync(l.counters.get(), 0, sizeof(Counters), stream));
    launch_attempt_boxes(dev_.view(), view, l.groups.get(), l.task_first.get(), n_groups, n_tasks, settings,
                         l.touch.get(), l.exact.get(), l.exact.size(), l.counters.get(), stream);
    if (detail_) l.busy.end(stream);
    CANOPY_CUDA_CHECK(
        cudaMemcpyAsync(&host, l.counters.get(), sizeof(Counters), cudaMemcpyDeviceToHost, stream));
    l.stream.synchronize();
    if (host.appended <= l.exact.size()) break;
    if (host.appended > std::numeric_limits<std::uint32_t>::max())
      throw std::length_error(
          fmt::format("bulk attempts: {} exact tests in one call (at most 2^32 - 1)", host.appended));
    l.exact.grow(host.appended + host.appended / 4);
  }
  const double t2 = now_seconds();
  if (detail_) l.busy.begin(stream);
  launch_attempt_exact(dev_.view(), view, l.groups.get(), l.exact.get(),
                       static_cast<std::uint32_t>(host.appended), l.touch.get(), l.counters.get(), stream);
  if (detail_) l.busy.end(stream);
  CANOPY_CUDA_CHECK(cudaMemcpyAsync(out.data(), l.touch.get(), groups.size() * sizeof(std::uint32_t),
                                    cudaMemcpyDeviceToHost, stream));
  // The exact kernel's count of touches, read back only for the statistics (a copy per call).
  if (detail_)
    CANOPY_CUDA_CHECK(
        cudaMemcpyAsync(&host, l.counters.get(), sizeof(Counters), cudaMemcpyDeviceToHost, stream));
  l.stream.synchronize();
  const double t3 = now_seconds();
  Stats& st = l.stats;
  st.upload_s += t1 - t0, st.box_s += t2 - t1, st.exact_s += t3 - t2;
  ++st.calls;
  st.groups += groups.size();
  st.box_tests += tasks;
  st.witness_hits += host.witness_hits;
  st.exact_touches += host.exact_touches;
  st.exact_tests += host.appended;
  st.seconds += now_seconds() - t0;
  return out;
}

}  // namespace canopy::cuda
