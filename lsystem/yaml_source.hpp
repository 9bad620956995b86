#pragma once
/// Helpers that read typed values out of yaml-cpp nodes and locate them in the source text, so
/// every grammar error can name file, line and column.
#include "lsystem/error.hpp"
#include "lsystem/scalar_places.hpp"

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace canopy {

/// A grammar file's text; throws GrammarFileError ("cannot open the grammar file") when it cannot
/// be opened, and GrammarError naming the file when it is not a regular file or is larger than
/// kMaxGrammarBytes (geometry/input_file.hpp).
std::string read_grammar_file(const std::string& path);
/// The YAML document in `text`; throws GrammarError at the parser's place ("malformed YAML: ...")
/// naming `file`.
YAML::Node parse_yaml_document(const std::string& text, const std::string& file);
/// A number's text without the '+' YAML's core schema allows before it (from_chars takes none):
/// grammar numbers and --set values alike.
std::string_view unsigned_text(std::string_view s);

class YamlSource {
 public:
  YamlSource(std::string file, std::string text) : file_(std::move(file)), text_(std::move(text)) {}

  const std::string& file() const { return file_; }
  /// Where `node` starts.
  SourcePos at(const YAML::Node& node) const;
  /// Where byte `offset` of a scalar node's value stands in the file, in any scalar style (escapes,
  /// folded lines and block scalars followed back to their source: lsystem/scalar_places.hpp).
  SourcePos at(const YAML::Node& node, std::size_t offset) const;

  double number(const YAML::Node& node, std::string_view what) const;
  long long integer(const YAML::Node& node, std::string_view what, long long lo, long long hi) const;
  std::uint64_t seed(const YAML::Node& node, std::string_view what) const;
  std::string string(const YAML::Node& node, std::string_view what) const;
  bool boolean(const YAML::Node& node, std::string_view what) const;
  /// Throws unless `node` is a map; checks every key against `allowed` (space separated;
  /// empty: any key) and that none appears twice.
  void check_map(const YAML::Node& node, std::string_view what, std::string_view allowed) const;
  void check_sequence(const YAML::Node& node, std::string_view what) const;

 private:
  std::string file_;
  std::string text_;
  mutable int places_of_ = -1;  // the node (its source offset) places_ belongs to
  mutable std::vector<SourcePlace> places_;
};

}  // namespace canopy
