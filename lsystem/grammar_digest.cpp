// A grammar file's identity for telling whether two runs used the same grammar (a resumed sweep
// compares it): its YAML document as yaml-cpp parses it, written out in one canonical form (maps,
// sequences and scalar values, each scalar with its length), so comments, blank lines,
// indentation, quoting and block or flow style change nothing, while any key, value or their
// order does.
#include "lsystem/error.hpp"
#include "lsystem/grammar.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <fstream>
#include <sstream>
#include <string_view>

namespace canopy {
namespace {

std::string fnv1a(std::string_view bytes) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (const char c : bytes) h = (h ^ static_cast<unsigned char>(c)) * 0x100000001b3ULL;
  return fmt::format("{:016x}", h);
}

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
    default:
      out += '~';
  }
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw GrammarFileError({path, 0, 0}, "cannot open the grammar file");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

std::string grammar_digest(const std::string& path) {
  const std::string text = read_file(path);
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw GrammarError({path, e.mark.line + 1, e.mark.column + 1}, "malformed YAML: " + e.msg);
  }
  std::string form;
  canonical(root, form);
  return fnv1a(form);
}

std::string grammar_text_digest(const std::string& path) { return fnv1a(read_file(path)); }

}  // namespace canopy
