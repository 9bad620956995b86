#pragma once
/// The CUDA detection backend: the same `detect(stand, request)` as the CPU backend, the same
/// contacts. Host: the tree's shape (the stand's structure alone), uploaded once per stand with
/// the stand; device: every box, refits, the plant grid, cluster pairs, organ pairs (sorted and
/// de-duplicated with CUB), the exact test and its compaction, each a balanced launch over a
/// compacted list. Only the final list (and a few counts) comes back.
#include "collision/backend.hpp"

#include <memory>

namespace canopy::cuda {

/// Throws CudaError when no device can be used.
std::unique_ptr<DetectionBackend> make_cuda_backend(int device = 0);

}  // namespace canopy::cuda
