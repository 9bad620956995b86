#include "lsystem/yaml_source.hpp"

#include "geometry/input_file.hpp"
#include "geometry/layout.hpp"
#include "lsystem/scalar_places.hpp"

#include <yaml-cpp/depthguard.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <unordered_set>
#include <vector>

namespace canopy {

std::string read_grammar_file(const std::string& path) {
  try {
    std::string text = read_input_file(path, "grammar file", kMaxGrammarBytes);
    // YAML cannot hold a NUL byte (yaml-cpp would report something else, somewhere else): a
    // binary or corrupt file, named at the byte.
    if (text.starts_with("\xFF\xFE") || text.starts_with("\xFE\xFF"))
      throw GrammarError({path, 1, 1}, "the file is UTF-16 text; a grammar is UTF-8 (save it as UTF-8)");
    if (const std::size_t nul = text.find('\0'); nul != std::string::npos) {
      const std::size_t line_start = text.rfind('\n', nul) + 1;  // npos + 1 == 0
      const int line = 1 + static_cast<int>(std::count(
                               text.begin(), text.begin() + static_cast<std::ptrdiff_t>(nul), '\n'));
      throw GrammarError({path, line, static_cast<int>(nul - line_start) + 1},
                         "a NUL byte: a grammar is UTF-8 text (is this a binary or corrupt file?)");
    }
    return text;
  } catch (const FileNotFound&) {
    throw GrammarFileError({path, 0, 0}, "cannot open the grammar file");
  } catch (const InputRefused& e) {
    throw GrammarError({path, e.line(), e.line() > 0 ? 1 : 0}, e.reason());
  }
}

namespace {

/// Where a second YAML document's first content stands in `text` (line and column, 1-based), or
/// line 0 where there is none. A document starts at a "---" line (column 0, then nothing, a space
/// or a tab) or after a "..." line; the first "---" starts the first document only where nothing
/// but comments, blank lines and directives came before it. Found in the text, not by parsing on
/// (yaml-cpp 0.7's LoadAll loops forever on some malformed text after a first document).
std::pair<int, int> second_document(std::string_view text) {
  const auto marker = [](std::string_view l, std::string_view m) {
    return l.starts_with(m) && (l.size() == 3 || l[3] == ' ' || l[3] == '\t');
  };
  const auto content_at = [](std::string_view l) -> int {  // column of content, 0 for none
    const std::size_t c = l.find_first_not_of(" \t");
    return c == std::string_view::npos || l[c] == '#' ? 0 : static_cast<int>(c) + 1;
  };
  int line = 0;
  bool content = false, started = false, ended = false;
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    std::string_view l = text.substr(at, end - at);
    at = end + 1;
    ++line;
    if (line == 1 && l.starts_with("\xEF\xBB\xBF")) l.remove_prefix(3);
    if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
    if (marker(l, "---")) {
      const bool next = content || started || ended;
      started = true, ended = false;
      if (const int c = content_at(l.substr(3))) {
        if (next) return {line, 3 + c};
        content = true;
      } else if (next) {
        content = false, ended = true;  // a new document, empty so far: its content would be the second's
      }
      continue;
    }
    if (marker(l, "...")) {
      ended = ended || content || started;
      continue;
    }
    if (!content && !started && l.starts_with('%')) continue;  // a directive
    if (const int c = content_at(l)) {
      if (ended) return {line, c};
      content = true;
    }
  }
  return {0, 0};
}

}  // namespace

YAML::Node parse_yaml_document(const std::string& text, const std::string& file) {
  try {
    // A grammar is one document: a second after '---' was read by nobody, its rules and organs
    // silently missing from the plants. (An empty one, a trailing '---', holds nothing to miss.)
    if (const auto [line, column] = second_document(text); line > 0)
      throw GrammarError({file, line, column},
                         "a second YAML document: a grammar is one document (merge it into the first, or "
                         "remove the '---' that starts it)");
    return YAML::Load(text);
  } catch (const YAML::DeepRecursion& e) {
    // yaml-cpp stops nesting at a bound of its own and says only "bad file".
    throw GrammarError({file, e.mark.line + 1, e.mark.column + 1},
                       "malformed YAML: lists and maps nested too deeply");
  } catch (const YAML::Exception& e) {
    throw GrammarError({file, e.mark.line + 1, e.mark.column + 1}, "malformed YAML: " + e.msg);
  }
}

SourcePos YamlSource::at(const YAML::Node& node) const {
  const YAML::Mark m = node.Mark();
  if (m.line < 0) return {file_, 0, 0};
  return {file_, m.line + 1, m.column + 1};
}

SourcePos YamlSource::at(const YAML::Node& node, std::size_t offset) const {
  SourcePos p = at(node);
  const YAML::Mark m = node.Mark();
  if (m.pos < 0 || static_cast<std::size_t>(m.pos) >= text_.size() || !node.IsScalar()) return p;
  // The places of the node's value, made once for the node (a production is located module by
  // module).
  if (places_of_ != m.pos) {
    places_ = scalar_places(text_, static_cast<std::size_t>(m.pos), p.line, p.column, node.Scalar());
    places_of_ = m.pos;
  }
  if (!places_.empty()) {
    const SourcePlace& q = places_[std::min(offset, places_.size() - 1)];
    return {file_, q.line, q.column};
  }
  // The source did not give the value as scalar_places reads it: the value's offset on the
  // node's line, past its quote.
  const char first = text_[static_cast<std::size_t>(m.pos)];
  if (first == '"' || first == '\'') return p.shifted(1 + static_cast<int>(offset));
  return p.shifted(static_cast<int>(offset));
}

std::string_view unsigned_text(std::string_view s) {
  if (s.size() > 1 && s[0] == '+' && (std::isdigit(static_cast<unsigned char>(s[1])) || s[1] == '.'))
    s.remove_prefix(1);
  return s;
}

double YamlSource::number(const YAML::Node& node, std::string_view what) const {
  if (!node.IsScalar()) fail_at(at(node), "{} must be a number", what);
  const std::string s = node.Scalar();
  const std::string_view t = unsigned_text(s);
  double v = 0;
  const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
  if (r.ec != std::errc() || r.ptr != t.data() + t.size() || !std::isfinite(v))
    fail_at(at(node), "{} must be a finite number, got '{}'", what, s);
  return v;
}

long long YamlSource::integer(const YAML::Node& node, std::string_view what, long long lo,
                              long long hi) const {
  if (!node.IsScalar()) fail_at(at(node), "{} must be a whole number", what);
  const std::string s = node.Scalar();
  const std::string_view t = unsigned_text(s);
  long long v = 0;
  const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
  if (r.ec != std::errc() || r.ptr != t.data() + t.size())
    fail_at(at(node), "{} must be a whole number, got '{}'", what, s);
  if (v < lo || v > hi) fail_at(at(node), "{} must be between {} and {}, got {}", what, lo, hi, v);
  return v;
}

std::uint64_t YamlSource::seed(const YAML::Node& node, std::string_view what) const {
  // A seed takes every value the command line's --seed and a positions file's seed cell take.
  const std::string s = node.IsScalar() ? node.Scalar() : std::string();
  const auto v = node.IsScalar() ? parse_seed(s) : std::nullopt;
  if (!v) fail_at(at(node), "{} must be a whole number from 0 to 18446744073709551615, got '{}'", what, s);
  return *v;
}

std::string YamlSource::string(const YAML::Node& node, std::string_view what) const {
  if (!node.IsScalar()) fail_at(at(node), "{} must be a string", what);
  return node.Scalar();
}

bool YamlSource::boolean(const YAML::Node& node, std::string_view what) const {
  if (node.IsScalar()) {
    const std::string s = node.Scalar();
    // YAML's core schema (true, True, TRUE) and YAML 1.1's yes/no/on/off, as YAML readers take them.
    for (const char* t : {"true", "True", "TRUE", "yes", "Yes", "YES", "on", "On", "ON"})
      if (s == t) return true;
    for (const char* f : {"false", "False", "FALSE", "no", "No", "NO", "off", "Off", "OFF"})
      if (s == f) return false;
  }
  fail_at(at(node), "{} must be true or false", what);
}

void YamlSource::check_map(const YAML::Node& node, std::string_view what, std::string_view allowed) const {
  if (!node.IsMap()) fail_at(at(node), "{} must be a map", what);
  std::unordered_set<std::string> seen;  // a set: a list made 100,000 constants take 14 s
  for (const auto& kv : node) {
    const std::string key = kv.first.Scalar();
    if (!seen.insert(key).second) fail_at(at(kv.first), "key '{}' appears twice in {}", key, what);
    if (allowed.empty()) continue;  // any key
    bool ok = false;
    std::size_t i = 0;
    while (i < allowed.size()) {
      std::size_t j = allowed.find(' ', i);
      if (j == std::string_view::npos) j = allowed.size();
      if (allowed.substr(i, j - i) == key) ok = true;
      i = j + 1;
    }
    if (!ok) fail_at(at(kv.first), "unknown key '{}' in {} (expected one of: {})", key, what, allowed);
  }
}

void YamlSource::check_sequence(const YAML::Node& node, std::string_view what) const {
  // A key with nothing after it (`productions:`) is YAML's null: an empty list, as `[]`.
  if (!node.IsSequence() && !node.IsNull()) fail_at(at(node), "{} must be a list", what);
}

}  // namespace canopy
