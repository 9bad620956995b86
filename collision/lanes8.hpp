#pragma once
/// Lanes of 8 floats or ints (GCC vector extensions, one AVX register each) and the few helpers
/// the CPU backend's 8-at-a-time tests share: organ boxes (collision/organ_rows.hpp), OBB pairs
/// (collision/obb_lanes.hpp) and the exact stage's triangle tests (collision/triangle_lanes.hpp). Each
/// such test does per lane the scalar predicate's very operations in its very order, so its
/// answers are the same bit for bit. Host only: nvcc never reads this file.
#include <cstdint>
#include <cstring>

namespace canopy {

namespace lanes_detail {
typedef float F8 __attribute__((vector_size(32)));
typedef int I8 __attribute__((vector_size(32)));
inline F8 load8(const float* p) {
  F8 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
/// The lanes at + t (t < 8) that lie below `count`, as bits: a run's last lanes masked off.
inline unsigned lanes_below(std::uint32_t count, std::uint32_t at) {
  return count - at < 8 ? (1u << (count - at)) - 1 : 0xffu;
}
inline unsigned bits8(I8 m) {
#if defined(__AVX__)
  return static_cast<unsigned>(__builtin_ia32_movmskps256(reinterpret_cast<F8>(m)));
#else
  unsigned b = 0;
  for (int t = 0; t < 8; ++t) b |= static_cast<unsigned>(m[t] & 1) << t;
  return b;
#endif
}
}  // namespace lanes_detail

}  // namespace canopy
