#pragma once
/// The text syntax of productions and module lists (ABOP / L-Py notation):
///   left_context < predecessor > right_context : condition -> successor : probability
#include "lsystem/error.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace canopy {

/// A piece of a production's text: [begin, end) offsets, or absent.
struct Span {
  std::size_t begin = 0, end = 0;
  bool present = false;
  std::string_view of(std::string_view text) const { return text.substr(begin, end - begin); }
};

struct ProductionParts {
  Span left, predecessor, right, condition, successor, probability;
};

/// Splits a production at its top-level (outside parentheses) `<`, `>`, `:`, `->` and `:`.
ProductionParts split_production(std::string_view text, const SourcePos& pos);

/// One module as written: its name, where it starts, and its argument texts.
struct RawModule {
  std::string name;
  std::size_t offset = 0;
  struct Arg {
    std::string_view text;
    std::size_t offset = 0;
  };
  std::vector<Arg> args;
};

/// Splits module lists into modules: declared names of several characters first, longest first;
/// any other character is a module of its own; white space separates; `(a, b)` follows a name.
class ModuleLexer {
 public:
  explicit ModuleLexer(const std::vector<std::string>& multi_char_names);
  /// Lexes `text`, found at `pos`; offsets in the result are relative to `text`.
  std::vector<RawModule> lex(std::string_view text, const SourcePos& pos) const;
  /// Length of the module name that starts at text[i].
  std::size_t name_length(std::string_view text, std::size_t i) const;

 private:
  /// The names as a trie, so that finding the longest at a place costs its length, not the
  /// number of names (a file of 65,000 names took minutes to lex name by name): the edge from a
  /// node by a byte, and whether a name ends at a node (node 0: the root).
  static std::uint64_t edge(std::uint32_t node, char c) {
    return std::uint64_t{node} << 8 | static_cast<unsigned char>(c);
  }
  std::unordered_map<std::uint64_t, std::uint32_t> edges_;
  std::vector<std::uint8_t> terminal_;
};

/// Length of the UTF-8 character that starts with byte `c` (1 for anything malformed).
std::size_t utf8_length(unsigned char c);

/// Whether `s` is well-formed UTF-8.
bool valid_utf8(std::string_view s);

/// A character no module name may hold: its byte offset, its code point and what it is.
struct UnusableCharacter {
  std::size_t offset = 0;
  char32_t code_point = 0;
  const char* what = "";
};
/// The first control character (C0 other than the white space lexers skip, DEL, C1) or
/// look-alike space (no-break, zero-width, ideographic, the byte-order mark) in well-formed
/// UTF-8 `s`; none: a usable name.
std::optional<UnusableCharacter> unusable_character(std::string_view s);

std::string_view trim(std::string_view s);
/// Offset of the first non-blank character of `s` within `s`.
std::size_t leading_blanks(std::string_view s);

}  // namespace canopy
