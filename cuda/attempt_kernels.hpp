#pragma once
/// The kernels of resolution's bulk attempts (resolution/attempt_batch.hpp): the boxes of every
/// (group, pair) at every axis of the group's mask, then a warp per pair whose boxes meet for
/// the exact test at the turned pose. Each group's answer is a mask of axes with a touching pair.
#include "resolution/attempt_batch.hpp"
#include "cuda/detect_kernels.hpp"

#include <cuda_runtime.h>

#include <cstdint>

namespace canopy::cuda {

struct AttemptTablesView {
  const std::int32_t* moving;
  const KeepEntry* keep;
  const PairEntry* pairs;
  const Vec3d* axes;
  const Obb* boxes;        // per organ of the stand: resolution's OBBs (no clearance)
  std::uint32_t* witness;  // per pair (AttemptTables::witness), brought up to date by the exact tests
};

/// A pair of a group whose boxes meet at one axis: the exact test decides.
struct ExactAttempt {
  std::uint32_t group, pair, axis;
};

/// Tasks t < n_tasks are (group g, its pair t - task_first[g]) with task_first ascending
/// (n_groups + 1 entries). Touching boxes set the axis bit in touch[g] at the organ level; at
/// the exact level a pair whose witness triangles touch at the turned pose sets it too (counted
/// in witness_hits), and the others append an ExactAttempt (past `capacity` only counted).
void launch_attempt_boxes(const StandView& v, AttemptTablesView t, const AttemptGroup* groups,
                          const std::uint32_t* task_first, std::uint32_t n_groups, std::uint32_t n_tasks,
                          AttemptSettings settings, std::uint32_t* touch, ExactAttempt* out,
                          unsigned long long capacity, Counters* counters, cudaStream_t stream = 0);
/// The exact test of each ExactAttempt (skipped where its axis already touches); a pair found
/// touching keeps the triangles that touched as its witness (counted in exact_touches).
void launch_attempt_exact(const StandView& v, AttemptTablesView t, const AttemptGroup* groups,
                          const ExactAttempt* tasks, std::uint32_t n, std::uint32_t* touch,
                          Counters* counters, cudaStream_t stream = 0);

}  // namespace canopy::cuda
