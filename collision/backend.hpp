#pragma once
/// The detection backend interface: `detect(stand, DetectRequest) -> Contacts`. The CPU
/// implementation lives here; the CUDA one in cuda/ implements the same interface, and the
/// command line (or a small factory) picks one, so collision/ never includes cuda/. Resolution's
/// bulk attempts are a second interface a backend may offer (resolution/attempt_source.hpp).
#include "collision/backend_failure.hpp"
#include "collision/contacts.hpp"
#include "collision/mbvt.hpp"
#include "geometry/stand.hpp"

#include <memory>
#include <string>
#include <vector>

namespace canopy {

struct DetectRequest {
  ContactLevel level = ContactLevel::exact;
  float clearance = 0;  // metres; with one, every bound at every level is inflated by it
  KindMask collide = default_collide_kinds();
  int threads = 0;  // 0: all cores
  /// When set (one flag per plant), only plant pairs with at least one flagged plant are looked
  /// at: the re-detection of resolution rounds (plants whose organs moved, and their neighbours).
  const std::vector<std::uint8_t>* active_plants = nullptr;
  /// When set (one flag per organ): the organs that moved since the contacts the caller holds.
  /// A backend may then leave out pairs (organ pairs, and at the leaf level cluster pairs) in
  /// which nothing moved (their answer cannot have changed); it may also report them, so the
  /// caller merges by pair.
  const std::vector<std::uint8_t>* moved_organs = nullptr;
  /// CUDA: device memory the detection may use, bytes (0: what the device has free). Stage
  /// lists that would not fit are made in batches of plant pairs.
  std::size_t max_device_bytes = 0;
  /// Host memory the contact lists may take, bytes (0: what the machine has available when the
  /// detection starts); collision/memory_budget.hpp.
  std::size_t memory_limit = 0;
};

/// The largest clearance (metres) detection and resolution take: past it every organ pair of a
/// field is a contact, and past 3e38 the clearance is no longer a float.
inline constexpr double kMaxClearance = 100;

/// Throws std::invalid_argument naming what is wrong when a request cannot be met: a clearance
/// that is negative, NaN, infinite or above kMaxClearance (every comparison with NaN is false, so a NaN clearance
/// would let every bound reject everything), or a negative thread count. Both backends call it
/// before anything else.
void check_request(const DetectRequest& request);

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
  /// Resolution rounds: organs `moved` have new transforms in `stand`. Refits the bounding
  /// volumes kept from the last detect() or redetect() on this stand (a transform per organ, not
  /// a rebuild; on CUDA only the moved organs travel to the device) and detects again.
  virtual Contacts redetect(const Stand& stand, const DetectRequest& request,
                            const std::vector<std::uint32_t>& moved) = 0;
  // Every member is pure: a backend that wraps another (resolution/auto_backend.hpp) must say
  // what it does with each, so none of the wrapped backend's paths is dropped unseen.
};

/// The CPU backend: MBVT, grid broad phase, parallel over plant pairs (OpenMP), results
/// independent of the thread count.
std::unique_ptr<DetectionBackend> make_cpu_backend();

}  // namespace canopy
