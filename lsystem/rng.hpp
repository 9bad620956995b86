#pragma once
/// The per-plant random stream: xoshiro256** (Blackman & Vigna 2018) seeded by splitmix64, so a
/// plant's draws depend on its own seed alone and are the same on every platform.
#include "geometry/mix64.hpp"

#include <cstdint>

namespace canopy {

class Rng {
 public:
  explicit Rng(std::uint64_t seed = 0) {
    for (auto& s : state_) s = splitmix64(seed);
  }
  std::uint64_t next() {
    const std::uint64_t result = rotl(state_[1] * 5, 7) * 9;
    const std::uint64_t t = state_[1] << 17;
    state_[2] ^= state_[0];
    state_[3] ^= state_[1];
    state_[1] ^= state_[2];
    state_[0] ^= state_[3];
    state_[2] ^= t;
    state_[3] = rotl(state_[3], 45);
    return result;
  }
  /// Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  /// Uniform in [a, b).
  double uniform(double a, double b) { return a + (b - a) * uniform(); }

  static std::uint64_t splitmix64(std::uint64_t& x) {
    const std::uint64_t z = mix64(x);
    x += kGoldenGamma;
    return z;
  }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t state_[4];
};

}  // namespace canopy
