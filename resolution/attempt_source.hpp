#pragma once
/// A detection backend that also runs resolution's turn-search attempts in bulk on its hardware
/// (the CUDA backend, and `--backend auto` around it): a second interface beside
/// DetectionBackend, so that the detection API (collision/backend.hpp) names no resolution type.
/// resolve() asks the backend it is given for this interface and plans through its runner where
/// it has one; the CPU backend has none and searches candidate by candidate.
#include "resolution/attempt_batch.hpp"
#include "collision/backend.hpp"
#include "geometry/stand.hpp"

namespace canopy {

class AttemptSource {
 public:
  virtual ~AttemptSource() = default;
  /// The runner of bulk attempts on this backend's hardware, for `stand` as the last detect() or
  /// redetect() saw it; null where the host's own search is the better choice. Pure, like every
  /// member of DetectionBackend: a backend that wraps another (auto_backend.hpp) must say what it
  /// does with it, so none of the wrapped backend's paths is dropped unseen.
  virtual AttemptRunner* attempt_runner(const Stand& stand) = 0;
};

/// The backend's runner source, or null where it has none.
inline AttemptSource* attempt_source(DetectionBackend& backend) {
  return dynamic_cast<AttemptSource*>(&backend);
}

}  // namespace canopy
