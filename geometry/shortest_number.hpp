#pragma once
/// Shortest round-trip text of floats and doubles, the same characters as std::to_chars(first,
/// last, value) with no format (the exports' contract: organs.csv reads back bit for bit), about
/// three times faster: the digits come from fmt's Dragonbox (the shortest decimal that reads back,
/// the nearest of those, ties to even: what libstdc++'s Ryu computes), then the layout std::to_chars
/// chooses, fixed or scientific, whichever is shorter (fixed on a tie). Checked against
/// std::to_chars on every float and on random and edge-case doubles (tests/geometry).
#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <cstring>

namespace canopy {
namespace detail {

inline constexpr char kDigitPairs[] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

inline int decimal_digits(std::uint64_t v) {
  static constexpr std::uint64_t kPow10[20] = {1ULL,
                                               10ULL,
                                               100ULL,
                                               1000ULL,
                                               10000ULL,
                                               100000ULL,
                                               1000000ULL,
                                               10000000ULL,
                                               100000000ULL,
                                               1000000000ULL,
                                               10000000000ULL,
                                               100000000000ULL,
                                               1000000000000ULL,
                                               10000000000000ULL,
                                               100000000000000ULL,
                                               1000000000000000ULL,
                                               10000000000000000ULL,
                                               100000000000000000ULL,
                                               1000000000000000000ULL,
                                               10000000000000000000ULL};
  const int bits = 64 - __builtin_clzll(v | 1);
  const int guess = bits * 1233 >> 12;  // floor(bits * log10(2)), at most one short
  return guess + (guess < 20 && v >= kPow10[guess]);
}

/// Writes the n digits of v (n = decimal_digits(v)) at out, most significant first, two at a
/// time (in 32 bits where v fits: the divisions by 100 are cheaper).
template <typename U>
inline void put_digit_pairs(char* out, U v, int n) {
  char* p = out + n;
  while (v >= 100) {
    const U q = v / 100;
    const auto two = static_cast<unsigned>(v - q * 100);
    v = q;
    p -= 2;
    std::memcpy(p, kDigitPairs + 2 * two, 2);
  }
  if (v >= 10) {
    std::memcpy(p - 2, kDigitPairs + 2 * v, 2);
  } else {
    p[-1] = static_cast<char>('0' + v);
  }
}
inline void put_digits(char* out, std::uint64_t v, int n) {
  if (v <= 0xffffffffu) put_digit_pairs(out, static_cast<std::uint32_t>(v), n);
  else put_digit_pairs(out, v, n);
}

/// A whole number's exact digits (std::to_chars' fixed form of one, as %.0f writes it).
inline char* put_whole(char* out, unsigned __int128 v) {
  char digits[48];
  int k = 0;
  do digits[k++] = static_cast<char>('0' + static_cast<int>(v % 10)), v /= 10;
  while (v);
  for (int i = 0; i < k; ++i) out[i] = digits[k - 1 - i];
  return out + k;
}

/// The decimal sig * 10^exp (sig without trailing zeros, at most 17 digits) of the positive
/// value v, as std::to_chars lays it out. Every copy has a fixed length (inlined, no library
/// call): `out` needs 64 bytes of room.
template <typename T>
char* layout_decimal(char* out, std::uint64_t sig, int exp, T v) {
  const int n = decimal_digits(sig);
  const int sci_exp = exp + n - 1;
  const int abs_exp = sci_exp < 0 ? -sci_exp : sci_exp;
  const int sci_len = n + (n > 1 ? 1 : 0) + 2 + (abs_exp >= 100 ? 3 : 2);
  const int fixed_len = exp >= 0 ? n + exp : (n + exp > 0 ? n + 1 : 2 - exp);
  char d[32];
  if (fixed_len <= sci_len) {
    // Only a whole number has exponent >= 0; below 10^22 (the largest the fixed form is chosen
    // for) it fits 128 bits. Its exact digits, not the shortest ones padded with zeros
    // (33584488 for the float 3.358449e7).
    if (exp >= 0) return put_whole(out, static_cast<unsigned __int128>(v));
    put_digits(d, sig, n);
    const int whole = n + exp;
    if (whole > 0) {  // the point among the digits; at most 16 after it
      std::memcpy(out, d, 20);
      out[whole] = '.';
      std::memcpy(out + whole + 1, d + whole, 16);
      return out + n + 1;
    }
    // 0.000ddd: the fixed form is chosen with at most four zeros after the point.
    std::memcpy(out, "0.0000", 6);
    std::memcpy(out + 2 - whole, d, 20);
    return out + 2 - whole + n;
  }
  put_digits(d, sig, n);
  out[0] = d[0];
  out[1] = '.';
  std::memcpy(out + 2, d + 1, 16);
  out += n > 1 ? n + 1 : 1;
  *out++ = 'e';
  *out++ = sci_exp < 0 ? '-' : '+';
  if (abs_exp >= 100) *out++ = static_cast<char>('0' + abs_exp / 100);
  std::memcpy(out, kDigitPairs + 2 * (abs_exp % 100), 2);
  return out + 2;
}

template <typename T>
char* shortest_chars(char* out, T v) {
  if (std::signbit(v)) *out++ = '-', v = -v;
  if (std::isnan(v)) return std::memcpy(out, "nan", 3), out + 3;
  if (std::isinf(v)) return std::memcpy(out, "inf", 3), out + 3;
  if (v == 0) return *out = '0', out + 1;
  const auto d = fmt::detail::dragonbox::to_decimal(v);
  return layout_decimal(out, d.significand, d.exponent, v);
}

}  // namespace detail

/// Writes v at out (64 bytes of room) as std::to_chars would; returns the end.
inline char* shortest_chars(char* out, float v) { return detail::shortest_chars(out, v); }
inline char* shortest_chars(char* out, double v) { return detail::shortest_chars(out, v); }

}  // namespace canopy
