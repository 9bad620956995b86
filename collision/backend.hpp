#pragma once
/// The detection backend interface: `detect(stand, DetectRequest) -> Contacts`. The CPU
/// implementation lives here; the CUDA one in cuda/ implements the same interface, and the
/// command line (or a small factory) picks one, so collision/ never includes cuda/.
#include "collision/contacts.hpp"
#include "collision/mbvt.hpp"
#include "geometry/stand.hpp"

#include <memory>
#include <string>

namespace canopy {

struct DetectRequest {
  ContactLevel level = ContactLevel::exact;
  float clearance = 0;  // metres; with one, every bound at every level is inflated by it
  KindMask collide = default_collide_kinds();
  int threads = 0;      // 0: all cores
};

/// The bounding-volume settings a request implies (same on every backend).
inline MbvtConfig mbvt_config(const DetectRequest& r) {
  MbvtConfig c;
  c.collide = r.collide;
  c.clearance = r.clearance;
  return c;
}

class DetectionBackend {
 public:
  virtual ~DetectionBackend() = default;
  virtual std::string name() const = 0;
  virtual std::string device() const = 0;
  /// Every contact at `request.level`, sorted, with the counts of every level up to it.
  virtual Contacts detect(const Stand& stand, const DetectRequest& request) = 0;
};

/// The CPU backend: MBVT, grid broad phase, parallel over plant pairs (OpenMP), results
/// independent of the thread count.
std::unique_ptr<DetectionBackend> make_cpu_backend();

}  // namespace canopy
