// Resolution's bulk attempts on the device: the shared CANOPY_HD box test of a turned pair
// (resolution/attempt_batch.hpp) and the shared warp exact test (cuda/organ_pair_test.cuh),
// compiled with --fmad=false like the host's -ffp-contract=off, so the answers are the host's.
#include "cuda/append.cuh"
#include "cuda/attempt_kernels.hpp"
#include "cuda/check.hpp"
#include "cuda/organ_pair_test.cuh"

namespace canopy::cuda {
namespace {

constexpr int kThreads = 128;

unsigned blocks(std::uint64_t n) { return static_cast<unsigned>((n + kThreads - 1) / kThreads); }

/// The group of task t: the last g with task_first[g] <= t.
__device__ std::uint32_t group_of(const std::uint32_t* task_first, std::uint32_t n_groups, std::uint32_t t) {
  std::uint32_t lo = 0, hi = n_groups;  // task_first[lo] <= t < task_first[hi]
  while (hi - lo > 1) {
    const std::uint32_t mid = (lo + hi) / 2;
    if (task_first[mid] <= t) lo = mid;
    else hi = mid;
  }
  return lo;
}

__global__ void attempt_boxes_kernel(StandView v, AttemptTablesView t, const AttemptGroup* groups,
                                     const std::uint32_t* task_first, std::uint32_t n_groups,
                                     std::uint32_t n_tasks, AttemptSettings settings, std::uint32_t* touch,
                                     ExactAttempt* out, unsigned long long capacity, Counters* c) {
  const std::uint32_t k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= n_tasks) return;
  const std::uint32_t gi = group_of(task_first, n_groups, k);
  const AttemptGroup g = groups[gi];
  const std::uint32_t p = g.pair_first + (k - task_first[gi]);
  const PairEntry pe = t.pairs[p];
  const KeepEntry y = t.keep[pe.keep];
  const auto xo = static_cast<std::uint32_t>(t.moving[pe.moving]), yo = static_cast<std::uint32_t>(y.organ);
  const Obb bx = t.boxes[xo], by = t.boxes[yo];
  const std::uint32_t witness = settings.exact ? t.witness[p] : kNoWitness;
  for (std::uint32_t i = 0; i < 32; ++i) {
    if (!(g.axis_mask >> i & 1u)) continue;
    const Motion turn = group_turn(g, t.axes[g.axis_first + i]);
    if (!turned_boxes_meet(bx, by, y, turn, settings.clearance)) continue;
    if (!settings.exact) {
      atomicOr(&touch[gi], 1u << i);
      continue;
    }
    // Another pair of the attempt touches already (the answer is an "any").
    if (*static_cast<volatile std::uint32_t*>(&touch[gi]) >> i & 1u) continue;
    // The triangles that touched last first: the same triangles usually still touch a few
    // degrees on, found by one thread instead of a warp's full test.
    if (witness != kNoWitness) {
      const Affine3f tx = apply(turn, v.transforms[xo]), ty = v.transforms[yo];
      // One call with the lower organ first (a second call site would inline the test twice).
      const bool low = xo < yo;
      if (witness_touches(v, low ? xo : yo, low ? tx : ty, low ? yo : xo, low ? ty : tx, witness, y.gap)) {
        atomicOr(&touch[gi], 1u << i);
        atomicAdd(&c->witness_hits, 1ull);
        continue;
      }
    }
    append(out, capacity, c, ExactAttempt{gi, p, i});
  }
}

/// At most 128 registers a thread (4 blocks an SM): the exact test needs many, and more warps
/// hide its latencies better than spilling costs.
__global__ void __launch_bounds__(kThreads, 4)
    attempt_exact_kernel(StandView v, AttemptTablesView t, const AttemptGroup* groups,
                         const ExactAttempt* tasks, std::uint32_t n, std::uint32_t* touch, Counters* c) {
  __shared__ volatile int done[kThreads / 32];
  __shared__ WarpStage stage[kThreads / 32];
  const std::uint64_t id = static_cast<std::uint64_t>(blockIdx.x) * blockDim.x + threadIdx.x;
  const auto k = static_cast<std::uint32_t>(id / 32);
  if (k >= n) return;  // whole warps
  const ExactAttempt task = tasks[k];
  const std::uint32_t bit = 1u << task.axis;
  // Another pair of this attempt may have touched already (the answer is an "any"); lane 0
  // reads for the whole warp, which must stay together for the warp test.
  std::uint32_t seen = 0;
  if (threadIdx.x % 32 == 0) seen = *static_cast<volatile std::uint32_t*>(&touch[task.group]);
  if (__shfl_sync(kFullWarp, seen, 0) & bit) return;
  const AttemptGroup g = groups[task.group];
  const PairEntry pe = t.pairs[task.pair];
  const auto xo = static_cast<std::uint32_t>(t.moving[pe.moving]);
  const KeepEntry& y = t.keep[pe.keep];
  const auto yo = static_cast<std::uint32_t>(y.organ);
  const Affine3f tx = apply(group_turn(g, t.axes[g.axis_first + task.axis]), v.transforms[xo]);
  const Affine3f ty = v.transforms[yo];
  volatile int& flag = done[threadIdx.x / 32];
  WarpStage* room = &stage[threadIdx.x / 32];
  // A touch found keeps its triangles as the pair's witness for the next levels (any axis's
  // will do: they serve only as the first thing to try).
  std::uint32_t* keep = &t.witness[task.pair];
  // One call with the lower organ first: the whole warp test is inlined once, not twice (the
  // kernel's code is large enough that instruction fetch is its first stall).
  const bool low = xo < yo;
  const bool found = warp_organs_touch(v, low ? xo : yo, low ? tx : ty, low ? yo : xo, low ? ty : tx, y.gap,
                                       flag, room, keep);
  if (found && threadIdx.x % 32 == 0) atomicOr(&touch[task.group], bit), atomicAdd(&c->exact_touches, 1ull);
}

}  // namespace

void launch_attempt_boxes(const StandView& v, AttemptTablesView t, const AttemptGroup* groups,
                          const std::uint32_t* task_first, std::uint32_t n_groups, std::uint32_t n_tasks,
                          AttemptSettings settings, std::uint32_t* touch, ExactAttempt* out,
                          unsigned long long capacity, Counters* counters, cudaStream_t stream) {
  if (!n_tasks) return;
  attempt_boxes_kernel<<<blocks(n_tasks), kThreads, 0, stream>>>(v, t, groups, task_first, n_groups, n_tasks,
                                                                 settings, touch, out, capacity, counters);
  CANOPY_CUDA_CHECK_LAUNCH("attempt_boxes_kernel");
}

void launch_attempt_exact(const StandView& v, AttemptTablesView t, const AttemptGroup* groups,
                          const ExactAttempt* tasks, std::uint32_t n, std::uint32_t* touch,
                          Counters* counters, cudaStream_t stream) {
  if (!n) return;
  attempt_exact_kernel<<<blocks(std::uint64_t{n} * 32), kThreads, 0, stream>>>(v, t, groups, tasks, n, touch,
                                                                               counters);
  CANOPY_CUDA_CHECK_LAUNCH("attempt_exact_kernel");
}

}  // namespace canopy::cuda
