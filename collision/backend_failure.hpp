#pragma once
/// What a backend throws when its hardware, not the request, failed (out of device memory, a lost
/// device): another backend can go on with the same stand and give the same answers. `--backend
/// auto` falls back to the CPU on it (resolution/auto_backend.hpp); any other error is the
/// request's and goes to the caller. Kept free of everything but <stdexcept> so that the CUDA
/// error type (cuda/check.hpp, included by nvcc-compiled files) can derive from it.
#include <stdexcept>

namespace canopy {

class BackendFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace canopy
