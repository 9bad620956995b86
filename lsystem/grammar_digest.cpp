// A grammar file's identity for telling whether two runs used the same grammar (a resumed sweep
// compares it): its YAML document as yaml-cpp parses it, written out in one canonical form (maps,
// sequences and scalar values, each scalar with its length), so comments, blank lines,
// indentation, quoting and block or flow style change nothing, while any key, value or their
// order does.
#include "geometry/fnv1a.hpp"
#include "lsystem/grammar.hpp"
#include "lsystem/yaml_source.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <string_view>

namespace canopy {
namespace {

std::string hex_digest(std::string_view bytes) { return fmt::format("{:016x}", fnv1a(bytes)); }

/// The tree in one form whatever its style: {key:value,...} [item,...] and LENGTH:scalar.
void canonical(const YAML::Node& node, std::string& out) {
  switch (node.Type()) {
    case YAML::NodeType::Map:
      out += '{';
      for (const auto& entry : node) {
        canonical(entry.first, out);
        out += ':';
        canonical(entry.second, out);
        out += ',';
      }
      out += '}';
      return;
    case YAML::NodeType::Sequence:
      out += '[';
      for (const auto& item : node) {
        canonical(item, out);
        out += ',';
      }
      out += ']';
      return;
    case YAML::NodeType::Scalar:
      out += fmt::format("{}:", node.Scalar().size());
      out += node.Scalar();
      return;
    default: out += '~';
  }
}

}  // namespace

std::string grammar_digest(const std::string& path) {
  const YAML::Node root = parse_yaml_document(read_grammar_file(path), path);
  std::string form;
  canonical(root, form);
  return hex_digest(form);
}

std::string grammar_text_digest(const std::string& path) { return hex_digest(read_grammar_file(path)); }

}  // namespace canopy
