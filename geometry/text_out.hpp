#pragma once
/// Fast number-to-text for exports: shortest round-trip floats and doubles, fixed decimals.
#include "geometry/shortest_number.hpp"

#include <charconv>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>

namespace canopy {

/// Appends `v` in shortest round-trip form (reads back to the same value).
template <typename T>
inline void append_number(std::string& out, T v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

/// Appends `v` with `decimals` fixed decimals, trailing zeros removed ("1.5", "-0.25", "3").
inline void append_fixed(std::string& out, double v, int decimals) {
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, decimals);
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
