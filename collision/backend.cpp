#include "collision/backend.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace canopy {

void check_request(const DetectRequest& r) {
  if (!std::isfinite(r.clearance) || r.clearance < 0 || r.clearance > kMaxClearance)
    throw std::invalid_argument(
        fmt::format("detection: the clearance must be a finite number of metres from 0 to {} (got {})",
                    kMaxClearance, r.clearance));
  if (r.threads < 0)
    throw std::invalid_argument(
        fmt::format("detection: the thread count must be at least 0 (0: all cores; got {})", r.threads));
}

}  // namespace canopy
