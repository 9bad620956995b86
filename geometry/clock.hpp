#pragma once
/// Wall time for the timings every library and tool reports: the steady clock (never set back)
/// read as seconds, and the seconds since a point of it. Host only.
#include <chrono>

namespace canopy {

/// Seconds on the steady clock since its arbitrary origin: only differences of two mean anything.
inline double now_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// Seconds from `start` (a std::chrono::steady_clock::now()) to now.
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace canopy
