#pragma once
/// FNV-1a, 64 bits: a stable hash of bytes for names and digests that must read the same on every
/// machine and run (a grammar's digest, a long folder name's staging stem).
#include <cstdint>
#include <string_view>

namespace canopy {

inline std::uint64_t fnv1a(std::string_view bytes) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (const char c : bytes) h = (h ^ static_cast<unsigned char>(c)) * 0x100000001b3ULL;
  return h;
}

}  // namespace canopy
