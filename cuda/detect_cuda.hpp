#pragma once
/// The CUDA detection backend: the same `detect(stand, request)` as the CPU backend, the same
/// contacts. Host: MBVT build and plant pairs; device: cluster pairs, organ pairs, exact test,
/// each a balanced launch over a compacted list.
#include "collision/backend.hpp"

#include <memory>

namespace canopy::cuda {

/// Throws CudaError when no device can be used.
std::unique_ptr<DetectionBackend> make_cuda_backend(int device = 0);

}  // namespace canopy::cuda
