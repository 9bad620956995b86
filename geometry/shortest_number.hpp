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

inline int decimal_digits(std::uint64_t v) {
  int n = 1;
  while (v >= 10) v /= 10, ++n;
  return n;
}

/// Writes the n digits of v (n = decimal_digits(v)) at out, most significant first.
inline void put_digits(char* out, std::uint64_t v, int n) {
  for (int i = n - 1; i >= 0; --i) out[i] = static_cast<char>('0' + v % 10), v /= 10;
}

/// The decimal sig * 10^exp (sig without trailing zeros) of the value `integer` holds when that
/// is a whole number, as std::to_chars lays it out.
inline char* layout_decimal(char* out, std::uint64_t sig, int exp, unsigned __int128 integer) {
  const int n = decimal_digits(sig);
  const int sci_exp = exp + n - 1;
  const int abs_exp = sci_exp < 0 ? -sci_exp : sci_exp;
  const int sci_len = n + (n > 1 ? 1 : 0) + 2 + (abs_exp >= 100 ? 3 : 2);
  const int fixed_len = exp >= 0 ? n + exp : (n + exp > 0 ? n + 1 : 2 - exp);
  if (fixed_len <= sci_len) {
    if (exp >= 0) {
      // A whole number in fixed form: std::to_chars writes its exact digits (as %.0f does), not
      // the shortest ones padded with zeros (33584488 for the float 3.358449e7).
      char digits[48];
      int k = 0;
      do digits[k++] = static_cast<char>('0' + static_cast<int>(integer % 10)), integer /= 10;
      while (integer);
      for (int i = 0; i < k; ++i) out[i] = digits[k - 1 - i];
      return out + k;
    }
    if (n + exp > 0) {  // the point among the digits
      const int whole = n + exp;
      char digits[24];
      put_digits(digits, sig, n);
      std::memcpy(out, digits, static_cast<std::size_t>(whole));
      out[whole] = '.';
      std::memcpy(out + whole + 1, digits + whole, static_cast<std::size_t>(n - whole));
      return out + n + 1;
    }
    out[0] = '0', out[1] = '.';
    const int zeros = -(n + exp);
    std::memset(out + 2, '0', static_cast<std::size_t>(zeros));
    put_digits(out + 2 + zeros, sig, n);
    return out + 2 + zeros + n;
  }
  char digits[24];
  put_digits(digits, sig, n);
  *out++ = digits[0];
  if (n > 1) {
    *out++ = '.';
    std::memcpy(out, digits + 1, static_cast<std::size_t>(n - 1));
    out += n - 1;
  }
  *out++ = 'e';
  *out++ = sci_exp < 0 ? '-' : '+';
  if (abs_exp >= 100) *out++ = static_cast<char>('0' + abs_exp / 100);
  *out++ = static_cast<char>('0' + abs_exp / 10 % 10);
  *out++ = static_cast<char>('0' + abs_exp % 10);
  return out;
}

template <typename T>
char* shortest_chars(char* out, T v) {
  if (std::signbit(v)) *out++ = '-', v = -v;
  if (std::isnan(v)) return std::memcpy(out, "nan", 3), out + 3;
  if (std::isinf(v)) return std::memcpy(out, "inf", 3), out + 3;
  if (v == 0) return *out = '0', out + 1;
  const auto d = fmt::detail::dragonbox::to_decimal(v);
  // Only a whole number has a shortest form with exponent >= 0; below 10^22 (the largest the
  // fixed form is chosen for) it fits 128 bits.
  const unsigned __int128 integer = d.exponent >= 0 && v < T(1e22) ? static_cast<unsigned __int128>(v) : 0;
  return layout_decimal(out, d.significand, d.exponent, integer);
}

}  // namespace detail

/// Writes v at out (at least 32 bytes of room) as std::to_chars would; returns the end.
inline char* shortest_chars(char* out, float v) { return detail::shortest_chars(out, v); }
inline char* shortest_chars(char* out, double v) { return detail::shortest_chars(out, v); }

}  // namespace canopy
