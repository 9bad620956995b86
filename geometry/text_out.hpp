#pragma once
/// Fast number-to-text for exports: shortest round-trip floats and doubles, fixed decimals.
/// Every conversion checks std::to_chars' result: a number that does not fit the buffer throws
/// (naming it) instead of appending bytes that were never written. Plant positions are bounded
/// before anything is grown (geometry/layout.hpp, kMaxPlantCoordinate), so exports never get
/// there; the check keeps a value from elsewhere from ever becoming raw memory in a file.
#include "geometry/shortest_number.hpp"

#include <charconv>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <type_traits>

namespace canopy {

namespace detail {
[[noreturn]] inline void number_too_long(double v, int decimals) {
  char shown[32];
  const auto r = std::to_chars(shown, shown + sizeof shown, v, std::chars_format::scientific, 6);
  throw std::range_error(
      std::string("cannot write the number ") + std::string(shown, r.ptr) +
      (decimals >= 0 ? " with " + std::to_string(decimals) + " fixed decimals" : std::string()) +
      ": it does not fit an export's number field");
}
}  // namespace detail

/// Appends `v` in shortest round-trip form (reads back to the same value).
template <typename T>
inline void append_number(std::string& out, T v) {
  char buf[64];  // a double's shortest form takes at most 24 characters, a 64-bit integer 20
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  if (r.ec != std::errc()) detail::number_too_long(static_cast<double>(v), -1);
  out.append(buf, r.ptr);
}

/// Appends `v` with `decimals` fixed decimals, trailing zeros removed ("1.5", "-0.25", "3").
inline void append_fixed(std::string& out, double v, int decimals) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, decimals);
  if (r.ec != std::errc()) detail::number_too_long(v, decimals);
  char* end = r.ptr;
  if (decimals > 0) {
    while (end[-1] == '0') --end;
    if (end[-1] == '.') --end;
  }
  if (end - buf == 2 && buf[0] == '-' && buf[1] == '0') {  // "-0" -> "0"
    out.push_back('0');
    return;
  }
  out.append(buf, end);
}

/// Floats and doubles: the same text as the template above (std::to_chars), made by
/// shortest_chars, three times faster (organs.csv is mostly floats).
inline void append_number(std::string& out, float v) {
  char buf[64];
  out.append(buf, shortest_chars(buf, v));
}
inline void append_number(std::string& out, double v) {
  char buf[64];
  out.append(buf, shortest_chars(buf, v));
}

/// The same text written at `p` (room for 64 characters), for a line made in a local buffer and
/// appended once: integers by std::to_chars, floats and doubles by shortest_chars.
template <typename T>
inline char* put_number(char* p, T v) {
  if constexpr (std::is_floating_point_v<T>) return shortest_chars(p, v);
  else return std::to_chars(p, p + 64, v).ptr;
}
inline char* put_text(char* p, std::string_view s) {
  std::memcpy(p, s.data(), s.size());
  return p + s.size();
}

}  // namespace canopy
