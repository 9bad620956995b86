#pragma once
/// splitmix64's step (Steele, Lea and Flood 2014): the golden-ratio increment, then its
/// finalizer. Every hash and seeded stream in canopy draws from it, so a draw depends on its
/// seed and index alone (any thread count, any backend).
#include "geometry/hd.hpp"

#include <cstdint>

namespace canopy {

inline constexpr std::uint64_t kGoldenGamma = 0x9e3779b97f4a7c15ULL;

/// The output of splitmix64 for state `x` (before its increment).
CANOPY_HD inline std::uint64_t mix64(std::uint64_t x) {
  x += kGoldenGamma;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

}  // namespace canopy
