#include "lsystem/production_syntax.hpp"

#include <algorithm>
#include <cctype>

namespace canopy {

std::string_view trim(std::string_view s) {
  const std::size_t b = leading_blanks(s);
  std::size_t e = s.size();
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(b, e - b);
}

std::size_t leading_blanks(std::string_view s) {
  std::size_t b = 0;
  while (b < s.size() && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  return b;
}

std::size_t utf8_length(unsigned char c) {
  if (c < 0x80) return 1;
  if ((c >> 5) == 0x6) return 2;
  if ((c >> 4) == 0xe) return 3;
  if ((c >> 3) == 0x1e) return 4;
  return 1;
}

bool valid_utf8(std::string_view s) {
  std::size_t i = 0;
  while (i < s.size()) {
    const auto c = static_cast<unsigned char>(s[i]);
    const std::size_t n = utf8_length(c);
    if (n == 1 && c >= 0x80) return false;
    if (i + n > s.size()) return false;
    for (std::size_t k = 1; k < n; ++k)
      if ((static_cast<unsigned char>(s[i + k]) & 0xc0) != 0x80) return false;
    i += n;
  }
  return true;
}

std::optional<UnusableCharacter> unusable_character(std::string_view s) {
  for (std::size_t i = 0; i < s.size();) {
    const auto c = static_cast<unsigned char>(s[i]);
    const std::size_t n = std::min(utf8_length(c), s.size() - i);
    char32_t cp = n == 1 ? c : c & (0x7f >> n);
    for (std::size_t k = 1; k < n; ++k) cp = (cp << 6) | (static_cast<unsigned char>(s[i + k]) & 0x3f);
    if (cp < 0x20 || (cp >= 0x7f && cp <= 0x9f)) return UnusableCharacter{i, cp, "a control character"};
    // Spaces a word processor or web page puts in for a plain one; and the byte-order mark.
    if (cp == 0xa0 || cp == 0x1680 || (cp >= 0x2000 && cp <= 0x200b) || cp == 0x2028 || cp == 0x2029 ||
        cp == 0x202f || cp == 0x205f || cp == 0x3000 || cp == 0xfeff)
      return UnusableCharacter{
          i, cp, "a no-break, zero-width or other Unicode space; separate modules with plain spaces"};
    i += n;
  }
  return std::nullopt;
}

namespace {

/// Offsets of every top-level occurrence of `tok` in [from, to), checking parentheses.
std::vector<std::size_t> top_level(std::string_view s, std::string_view tok, std::size_t from, std::size_t to,
                                   const SourcePos& pos) {
  std::vector<std::size_t> hits;
  int depth = 0;
  std::size_t outer = 0;  // the '(' that opened depth 1 last
  for (std::size_t i = from; i < to; ++i) {
    const char c = s[i];
    if (c == '(') {
      if (depth++ == 0) outer = i;
    } else if (c == ')') {
      if (--depth < 0) fail_at(pos.shifted(static_cast<int>(i)), "')' without a matching '('");
    } else if (depth == 0 && s.substr(i, tok.size()) == tok && i + tok.size() <= to) {
      hits.push_back(i);
    }
  }
  // A '(' left open hides everything after it (an arrow too): it is the error to name.
  if (depth > 0) fail_at(pos.shifted(static_cast<int>(outer)), "this '(' is never closed");
  return hits;
}

Span make_span(std::string_view s, std::size_t b, std::size_t e) {
  const std::string_view piece = s.substr(b, e - b);
  const std::size_t lead = leading_blanks(piece);
  const std::size_t len = trim(piece).size();
  return {b + lead, b + lead + len, true};
}

}  // namespace

ProductionParts split_production(std::string_view s, const SourcePos& pos) {
  ProductionParts p;
  const auto arrows = top_level(s, "->", 0, s.size(), pos);
  if (arrows.empty()) fail_at(pos, "expected '->' in production '{}'", s);
  if (arrows.size() > 1) fail_at(pos.shifted(static_cast<int>(arrows[1])), "a production has one '->'");
  const std::size_t arrow = arrows[0];

  // Left-hand side: [left <] predecessor [> right] [: condition]
  std::size_t head_end = arrow;
  if (auto colons = top_level(s, ":", 0, arrow, pos); !colons.empty()) {
    head_end = colons[0];
    p.condition = make_span(s, colons[0] + 1, arrow);
    if (p.condition.begin == p.condition.end)
      fail_at(pos.shifted(static_cast<int>(colons[0])), "empty condition after ':'");
  }
  std::size_t pred_begin = 0, pred_end = head_end;
  if (auto lt = top_level(s, "<", 0, head_end, pos); !lt.empty()) {
    if (lt.size() > 1)
      fail_at(pos.shifted(static_cast<int>(lt[1])), "a production has at most one '<' before its condition");
    p.left = make_span(s, 0, lt[0]);
    pred_begin = lt[0] + 1;
  }
  if (auto gt = top_level(s, ">", pred_begin, head_end, pos); !gt.empty()) {
    if (gt.size() > 1)
      fail_at(pos.shifted(static_cast<int>(gt[1])), "a production has at most one '>' before its condition");
    p.right = make_span(s, gt[0] + 1, head_end);
    pred_end = gt[0];
  }
  p.predecessor = make_span(s, pred_begin, pred_end);
  if (p.predecessor.begin == p.predecessor.end)
    fail_at(pos.shifted(static_cast<int>(pred_begin)), "missing predecessor before '->'");

  // Right-hand side: successor [: probability]
  std::size_t succ_end = s.size();
  if (auto colons = top_level(s, ":", arrow + 2, s.size(), pos); !colons.empty()) {
    succ_end = colons.back();
    p.probability = make_span(s, colons.back() + 1, s.size());
    if (p.probability.begin == p.probability.end)
      fail_at(pos.shifted(static_cast<int>(colons.back())), "empty probability after ':'");
  }
  p.successor = make_span(s, arrow + 2, succ_end);
  return p;
}

ModuleLexer::ModuleLexer(const std::vector<std::string>& names) : terminal_(1, 0) {
  for (const std::string& n : names) {
    std::uint32_t node = 0;
    for (const char c : n) {
      const auto [it, added] =
          edges_.try_emplace(edge(node, c), static_cast<std::uint32_t>(terminal_.size()));
      if (added) terminal_.push_back(0);
      node = it->second;
    }
    terminal_[node] = 1;
  }
}

std::size_t ModuleLexer::name_length(std::string_view text, std::size_t i) const {
  // The longest declared name that starts here: a walk down the trie as far as the text goes.
  std::size_t longest = 0;
  std::uint32_t node = 0;
  for (std::size_t k = i; k < text.size(); ++k) {
    const auto it = edges_.find(edge(node, text[k]));
    if (it == edges_.end()) break;
    node = it->second;
    if (terminal_[node]) longest = k - i + 1;
  }
  if (longest) return longest;
  return std::min(utf8_length(static_cast<unsigned char>(text[i])), text.size() - i);
}

std::vector<RawModule> ModuleLexer::lex(std::string_view text, const SourcePos& pos) const {
  std::vector<RawModule> out;
  std::size_t i = 0;
  const auto at = [&](std::size_t k) { return pos.shifted(static_cast<int>(k)); };
  while (i < text.size()) {
    if (std::isspace(static_cast<unsigned char>(text[i]))) {
      ++i;
      continue;
    }
    const char c = text[i];
    if (c == '(') fail_at(at(i), "'(' must follow a module name");
    if (c == ')') fail_at(at(i), "')' without a matching '('");
    if (c == ',') fail_at(at(i), "',' outside a module's parameter list");
    RawModule m;
    m.offset = i;
    const std::size_t len = name_length(text, i);
    if (!valid_utf8(text.substr(i, len))) fail_at(at(i), "invalid UTF-8 in a module name");
    if (const auto bad = unusable_character(text.substr(i, len)))
      fail_at(at(i + bad->offset), "character U+{:04X} cannot be part of a module name: {}",
              static_cast<std::uint32_t>(bad->code_point), bad->what);
    m.name = std::string(text.substr(i, len));
    i += len;
    std::size_t j = i;
    while (j < text.size() && std::isspace(static_cast<unsigned char>(text[j]))) ++j;
    if (j < text.size() && text[j] == '(') {
      const std::size_t open = j;
      int depth = 0;
      std::size_t arg_start = open + 1;
      for (j = open; j < text.size(); ++j) {
        if (text[j] == '(') ++depth;
        else if (text[j] == ')' && --depth == 0) break;
        else if (text[j] == ',' && depth == 1) {
          m.args.push_back({text.substr(arg_start, j - arg_start), arg_start});
          arg_start = j + 1;
        }
      }
      if (j >= text.size()) fail_at(at(open), "'(' after '{}' is never closed", m.name);
      const std::string_view last = text.substr(arg_start, j - arg_start);
      if (!m.args.empty() || !trim(last).empty()) m.args.push_back({last, arg_start});
      for (const auto& a : m.args)
        if (trim(a.text).empty()) fail_at(at(a.offset), "empty parameter in '{}'", m.name);
      i = j + 1;
    }
    out.push_back(std::move(m));
  }
  return out;
}

}  // namespace canopy
