#pragma once
/// Lanes of 8 floats or ints (GCC vector extensions, one AVX register each) and the few helpers
/// the CPU backend's 8-at-a-time tests share: organ boxes (collision/organ_rows.hpp), OBB pairs
/// (collision/obb_lanes.hpp) and the exact stage's triangle tests (collision/triangle_lanes.hpp). Each
/// such test does per lane the scalar predicate's very operations in its very order, so its
/// answers are the same bit for bit. Host only: nvcc never reads this file.
#include <cmath>
#include <cstdint>
#include <cstring>
#if defined(__AVX__)
#include <immintrin.h>
#endif

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
inline F8 splat8(float x) { return F8{x, x, x, x, x, x, x, x}; }  // x in every lane
inline F8 min8(F8 a, F8 b) { return a < b ? a : b; }  // min_f lane by lane
inline F8 max8(F8 a, F8 b) { return a > b ? a : b; }  // max_f lane by lane
inline F8 sqrt8(F8 v) {  // sqrtf lane by lane (both correctly rounded)
#if defined(__AVX__)
  __m256 r;
  std::memcpy(&r, &v, sizeof v);
  r = _mm256_sqrt_ps(r);
  std::memcpy(&v, &r, sizeof v);
#else
  for (int t = 0; t < 8; ++t) v[t] = std::sqrt(v[t]);
#endif
  return v;
}
}  // namespace lanes_detail

}  // namespace canopy
