#pragma once
/// Lanes of 8 floats or ints (GCC vector extensions, one AVX register each) and the few helpers
/// the CPU backend's 8-at-a-time tests share: organ boxes (collision/lanes/organ_rows.hpp), OBB pairs
/// (collision/lanes/obb_lanes.hpp) and the exact stage's triangle tests (collision/lanes/triangle_lanes.hpp).
/// Each such test does per lane the scalar predicate's very operations in its very order, so its answers are
/// the same bit for bit. Host only: nvcc never reads this file.
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
/// Stores 8 lanes at p (unaligned) from a register: a copy of an array element through
/// memcpy went through the stack 16 bytes at a time (collision/exact.cpp, posing).
inline void store8(float* p, F8 v) {
#if defined(__AVX__)
  _mm256_storeu_ps(p, reinterpret_cast<__m256>(v));
#else
  std::memcpy(p, &v, sizeof v);
#endif
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
/// out[k] lane t = rows[t][k] (k, t < 8): 8 records of 8 floats into lanes by component, an
/// 8 x 8 transpose of registers (one load per record rather than a gather per component).
inline void transpose8(const float* const* rows, F8* out) {
#if defined(__AVX__)
  __m256 r[8];
  for (int t = 0; t < 8; ++t) r[t] = _mm256_loadu_ps(rows[t]);
  __m256 u[8], v[8];
  for (int t = 0; t < 8; t += 2)
    u[t] = _mm256_unpacklo_ps(r[t], r[t + 1]), u[t + 1] = _mm256_unpackhi_ps(r[t], r[t + 1]);
  for (int t = 0; t < 8; t += 4) {
    v[t] = _mm256_shuffle_ps(u[t], u[t + 2], _MM_SHUFFLE(1, 0, 1, 0));
    v[t + 1] = _mm256_shuffle_ps(u[t], u[t + 2], _MM_SHUFFLE(3, 2, 3, 2));
    v[t + 2] = _mm256_shuffle_ps(u[t + 1], u[t + 3], _MM_SHUFFLE(1, 0, 1, 0));
    v[t + 3] = _mm256_shuffle_ps(u[t + 1], u[t + 3], _MM_SHUFFLE(3, 2, 3, 2));
  }
  for (int k = 0; k < 4; ++k) {
    const __m256 lo = _mm256_permute2f128_ps(v[k], v[k + 4], 0x20),
                 hi = _mm256_permute2f128_ps(v[k], v[k + 4], 0x31);
    std::memcpy(&out[k], &lo, sizeof lo);
    std::memcpy(&out[k + 4], &hi, sizeof hi);
  }
#else
  for (int t = 0; t < 8; ++t)
    for (int k = 0; k < 8; ++k) out[k][t] = rows[t][k];
#endif
}
inline F8 splat8(float x) { return F8{x, x, x, x, x, x, x, x}; }  // x in every lane
inline F8 abs8(F8 v) {                                            // fabsf lane by lane (the sign bit cleared)
  I8 bits;
  std::memcpy(&bits, &v, sizeof v);
  bits &= 0x7fffffff;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}
inline F8 min8(F8 a, F8 b) { return a < b ? a : b; }  // min_f lane by lane
inline F8 max8(F8 a, F8 b) { return a > b ? a : b; }  // max_f lane by lane
/// The least and the greatest of 8 lanes holding no NaN (halves, then quarters, then pairs: the
/// value a scan lane by lane gives, a zero's sign aside, which no comparison sees).
inline float least8(F8 v) {
  v = min8(v, __builtin_shuffle(v, I8{4, 5, 6, 7, 0, 1, 2, 3}));
  v = min8(v, __builtin_shuffle(v, I8{2, 3, 0, 1, 6, 7, 4, 5}));
  return min8(v, __builtin_shuffle(v, I8{1, 0, 3, 2, 5, 4, 7, 6}))[0];
}
inline float greatest8(F8 v) {
  v = max8(v, __builtin_shuffle(v, I8{4, 5, 6, 7, 0, 1, 2, 3}));
  v = max8(v, __builtin_shuffle(v, I8{2, 3, 0, 1, 6, 7, 4, 5}));
  return max8(v, __builtin_shuffle(v, I8{1, 0, 3, 2, 5, 4, 7, 6}))[0];
}
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
