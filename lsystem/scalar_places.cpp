#include "lsystem/scalar_places.hpp"

#include <cstdint>

namespace canopy {
namespace {

void append_utf8(std::string& out, std::uint32_t c) {
  if (c < 0x80) {
    out += static_cast<char>(c);
  } else if (c < 0x800) {
    out += static_cast<char>(0xC0 | (c >> 6));
    out += static_cast<char>(0x80 | (c & 0x3F));
  } else if (c < 0x10000) {
    out += static_cast<char>(0xE0 | (c >> 12));
    out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (c & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (c >> 18));
    out += static_cast<char>(0x80 | ((c >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (c & 0x3F));
  }
}

/// The bytes a double-quoted scalar's escape at text[s] ('\\') stands for, and its length in
/// `length`; false for an escape YAML does not have (the caller gives up).
bool decode_escape(std::string_view text, std::size_t s, std::string& bytes, std::size_t& length) {
  bytes.clear();
  if (s + 1 >= text.size()) return false;
  const char e = text[s + 1];
  length = 2;
  int hex = 0;
  switch (e) {
    case '0': bytes = std::string(1, '\0'); return true;
    case 'a': bytes = "\a"; return true;
    case 'b': bytes = "\b"; return true;
    case 't':
    case '\t': bytes = "\t"; return true;
    case 'n': bytes = "\n"; return true;
    case 'v': bytes = "\v"; return true;
    case 'f': bytes = "\f"; return true;
    case 'r': bytes = "\r"; return true;
    case 'e': bytes = "\x1b"; return true;
    case ' ': bytes = " "; return true;
    case '"': bytes = "\""; return true;
    case '/': bytes = "/"; return true;
    case '\\': bytes = "\\"; return true;
    case 'N': append_utf8(bytes, 0x85); return true;
    case '_': append_utf8(bytes, 0xA0); return true;
    case 'L': append_utf8(bytes, 0x2028); return true;
    case 'P': append_utf8(bytes, 0x2029); return true;
    case 'x': hex = 2; break;
    case 'u': hex = 4; break;
    case 'U': hex = 8; break;
    default: return false;
  }
  if (s + 2 + static_cast<std::size_t>(hex) > text.size()) return false;
  std::uint32_t c = 0;
  for (int k = 0; k < hex; ++k) {
    const char h = text[s + 2 + static_cast<std::size_t>(k)];
    const int d = h >= '0' && h <= '9'   ? h - '0'
                  : h >= 'a' && h <= 'f' ? h - 'a' + 10
                  : h >= 'A' && h <= 'F' ? h - 'A' + 10
                                         : -1;
    if (d < 0) return false;
    c = c * 16 + static_cast<std::uint32_t>(d);
  }
  if (c > 0x10FFFF) return false;
  append_utf8(bytes, c);
  length = 2 + static_cast<std::size_t>(hex);
  return true;
}

bool blank(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

}  // namespace

std::vector<SourcePlace> scalar_places(std::string_view text, std::size_t start, int line, int column,
                                       const std::string& value) {
  if (start >= text.size()) return {};
  std::size_t s = start;
  SourcePlace at{line, column};
  const auto step = [&] {
    if (text[s] == '\n') ++at.line, at.column = 1;
    else ++at.column;
    ++s;
  };
  const char first = text[start];
  const bool double_quoted = first == '"', single_quoted = first == '\'';
  if (double_quoted || single_quoted) {
    step();
  } else if (first == '|' || first == '>') {
    while (s < text.size() && text[s] != '\n') step();  // the header: indicators, a comment
    if (s < text.size()) step();
  }
  std::vector<SourcePlace> places;
  places.reserve(value.size() + 1);
  std::string bytes;
  for (std::size_t i = 0; i < value.size();) {
    if (s >= text.size()) return {};
    const char c = text[s];
    if (double_quoted && c == '\\') {
      if (s + 1 < text.size() && (text[s + 1] == '\n' || text[s + 1] == '\r')) {  // a line continued
        step();
        continue;
      }
      std::size_t length = 0;
      if (!decode_escape(text, s, bytes, length) || value.compare(i, bytes.size(), bytes) != 0) return {};
      for (std::size_t k = 0; k < bytes.size(); ++k) places.push_back(at);
      i += bytes.size();
      for (std::size_t k = 0; k < length; ++k) step();
      continue;
    }
    if (single_quoted && c == '\'' && s + 1 < text.size() && text[s + 1] == '\'') {
      if (value[i] != '\'') return {};
      places.push_back(at);
      ++i;
      step(), step();
      continue;
    }
    if (c == value[i] || (value[i] == ' ' && c == '\n')) {  // the byte itself, or a break read as a space
      places.push_back(at);
      ++i;
      step();
      continue;
    }
    if (!blank(c)) return {};  // not this value's source
    step();                    // white space or a break the value dropped
  }
  places.push_back(at);
  return places;
}

}  // namespace canopy
