#include "cuda/attempt_runner_cuda.hpp"

#include "cuda/scatter.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cstdlib>
#include <limits>
#include <stdexcept>

namespace canopy::cuda {
namespace {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

}  // namespace

CudaAttemptRunner::CudaAttemptRunner(const StandOnDevice& dev) : dev_(dev) {
  counters_.resize(1);
  exact_.resize(1 << 20);
}

CudaAttemptRunner::~CudaAttemptRunner() {
  if (report_)
    fmt::print(stderr, "bulk attempts on the device: {} calls, {} groups, {} box tests, {} witness hits, {} exact tests ({} touching), {:.1f} MB up; {:.3f} s ({:.3f} up, {:.3f} boxes, {:.3f} exact)\n",
               stats_.calls, stats_.groups, stats_.box_tests, stats_.witness_hits, stats_.exact_tests, stats_.exact_touches,
               stats_.uploaded_bytes / 1e6, stats_.seconds, stats_.upload_s, stats_.box_s, stats_.exact_s);
}

void CudaAttemptRunner::update_organs(const Stand& stand, std::span<const Obb> boxes, std::span<const std::uint32_t> changed,
                                      bool all) {
  if (boxes.size() != stand.organ_count()) throw std::logic_error("bulk attempts: one box per organ expected");
  if (all || boxes_.size() != boxes.size()) {
    if (!all) throw std::logic_error("bulk attempts: organs changed before the runner saw them all");
    boxes_.resize(boxes.size());
    boxes_.upload_at(0, boxes.data(), boxes.size());
    stats_.uploaded_bytes += boxes.size() * sizeof(Obb);
    return;
  }
  scatter_from_host(boxes_.get(), boxes.data(), changed, staged_ids_, staged_boxes_);
  stats_.uploaded_bytes += changed.size() * (sizeof(Obb) + sizeof(std::uint32_t));
}

void CudaAttemptRunner::clear() { moving_sent_ = keep_sent_ = pairs_sent_ = witness_sent_ = axes_sent_ = 0; }

std::vector<std::uint32_t> CudaAttemptRunner::touching(const AttemptTables& t, std::span<const AttemptGroup> groups,
                                                       const AttemptSettings& settings) {
  std::vector<std::uint32_t> out(groups.size(), 0);
  if (groups.empty()) return out;
  const double t0 = now();
  if (t.moving.size() < moving_sent_ || t.keep.size() < keep_sent_ || t.pairs.size() < pairs_sent_ || t.axes.size() < axes_sent_ ||
      t.witness.size() < witness_sent_)
    throw std::logic_error("bulk attempts: the tables shrank without a clear()");
  if (t.witness.size() != t.pairs.size()) throw std::logic_error("bulk attempts: one witness per pair expected");
  stats_.uploaded_bytes += (t.moving.size() - moving_sent_) * sizeof(std::int32_t) + (t.keep.size() - keep_sent_) * sizeof(KeepEntry) +
                           (t.pairs.size() - pairs_sent_) * (sizeof(PairEntry) + sizeof(std::uint32_t)) +
                           groups.size() * sizeof(AttemptGroup);
  sync(moving_, t.moving, moving_sent_);
  sync(keep_, t.keep, keep_sent_);
  sync(pairs_, t.pairs, pairs_sent_);
  sync(witness_, t.witness, witness_sent_);  // new pairs only: the device keeps its own up to date
  sync(axes_, t.axes, axes_sent_);
  // Task t of the box kernel: (group g, pair t - first[g]).
  std::vector<std::uint32_t> first(groups.size() + 1, 0);
  std::uint64_t tasks = 0;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    first[g] = static_cast<std::uint32_t>(tasks);
    tasks += groups[g].pair_end - groups[g].pair_first;
  }
  if (tasks > std::numeric_limits<std::uint32_t>::max())
    throw std::length_error(fmt::format("bulk attempts: {} pair tests in one call (at most 2^32 - 1)", tasks));
  first[groups.size()] = static_cast<std::uint32_t>(tasks);
  groups_.grow(groups.size());
  groups_.upload_at(0, groups.data(), groups.size());
  task_first_.grow(first.size());
  task_first_.upload_at(0, first.data(), first.size());
  touch_.grow(groups.size());
  CANOPY_CUDA_CHECK(cudaMemset(touch_.get(), 0, groups.size() * sizeof(std::uint32_t)));
  if (boxes_.size() != dev_.organs()) throw std::logic_error("bulk attempts: update_organs() not called for this stand");
  const AttemptTablesView view{moving_.get(), keep_.get(), pairs_.get(), axes_.get(), boxes_.get(), witness_.get()};
  const auto n_groups = static_cast<std::uint32_t>(groups.size()), n_tasks = static_cast<std::uint32_t>(tasks);
  // The exact tests are listed with a capacity; a list that overflows is made again, larger.
  CANOPY_CUDA_CHECK(cudaDeviceSynchronize());
  const double t1 = now();
  Counters host{};
  for (;;) {
    CANOPY_CUDA_CHECK(cudaMemset(counters_.get(), 0, sizeof(Counters)));
    launch_attempt_boxes(dev_.view(), view, groups_.get(), task_first_.get(), n_groups, n_tasks, settings, touch_.get(), exact_.get(),
                         exact_.size(), counters_.get());
    CANOPY_CUDA_CHECK(cudaMemcpy(&host, counters_.get(), sizeof(Counters), cudaMemcpyDeviceToHost));
    if (host.appended <= exact_.size()) break;
    if (host.appended > std::numeric_limits<std::uint32_t>::max())
      throw std::length_error(fmt::format("bulk attempts: {} exact tests in one call (at most 2^32 - 1)", host.appended));
    exact_.resize(host.appended + host.appended / 4);
  }
  const double t2 = now();
  launch_attempt_exact(dev_.view(), view, groups_.get(), exact_.get(), static_cast<std::uint32_t>(host.appended), touch_.get(),
                       counters_.get());
  CANOPY_CUDA_CHECK(cudaMemcpy(out.data(), touch_.get(), groups.size() * sizeof(std::uint32_t), cudaMemcpyDeviceToHost));
  // The exact kernel's count of touches, read back only for the report (a copy per call).
  if (report_) CANOPY_CUDA_CHECK(cudaMemcpy(&host, counters_.get(), sizeof(Counters), cudaMemcpyDeviceToHost));
  const double t3 = now();
  stats_.upload_s += t1 - t0, stats_.box_s += t2 - t1, stats_.exact_s += t3 - t2;
  ++stats_.calls;
  stats_.groups += groups.size();
  stats_.box_tests += tasks;
  stats_.witness_hits += host.witness_hits;
  stats_.exact_touches += host.exact_touches;
  stats_.exact_tests += host.appended;
  stats_.seconds += now() - t0;
  return out;
}

}  // namespace canopy::cuda
