#pragma once
/// A loaded grammar file (docs/design.md "Grammar file"): symbols, compiled productions, organs.
#include "geometry/organ_kind.hpp"
#include "lsystem/error.hpp"
#include "lsystem/expr.hpp"
#include "lsystem/module_string.hpp"

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace canopy {

/// The most formal parameters one production may bind (predecessor and contexts together).
inline constexpr int kMaxFrame = 64;

/// A module in a predecessor or context: its symbol and where its formal parameters go in the
/// production's frame.
struct ModulePattern {
  Symbol symbol = 0;
  int first_slot = 0;
  SourcePos pos;
};

/// A module of a successor (or of the axiom): its symbol and one expression per parameter.
struct SuccessorModule {
  Symbol symbol = 0;
  std::vector<Expr> args;
  SourcePos pos;
};

struct Successor {
  std::vector<SuccessorModule> modules;
  SourcePos pos;          // its production (a group's members each have their own)
  double cumulative = 1;  // upper end of this successor's share of [0, 1)
  /// When every argument is a literal: the modules ready to copy.
  bool constant = false;
  std::vector<Symbol> constant_symbols;
  std::vector<double> constant_params;
};

/// Productions that share predecessor, contexts and condition: one stochastic group (a
/// deterministic production is a group of one).
struct RuleGroup {
  std::vector<ModulePattern> left;  // in text order; the last one is the nearest
  ModulePattern predecessor;
  std::vector<ModulePattern> right;  // in text order; the first one is the nearest
  std::optional<Expr> condition;
  std::vector<Successor> successors;
  int frame_size = 0;
  SourcePos pos;
  std::string key;  // normalised text of contexts, predecessor and condition
};

/// How a symbol is rewritten, chosen once at load so the derivation loop can take fast paths.
enum class RewriteMode : std::uint8_t { copy, constant, general };

struct RuleTable {
  std::vector<RuleGroup> groups;
  std::vector<std::vector<int>> by_symbol;  // group indices per symbol, in file order
  std::vector<RewriteMode> mode;            // per symbol
  bool context_sensitive = false;
  bool empty() const { return groups.empty(); }
};

struct OrganEntry {
  PrototypeKind prototype = PrototypeKind::cylinder;
  OrganKind kind = OrganKind::internode;
  double joint_limit_deg = 60;
  std::optional<int> lod;
  SourcePos pos;
};

struct Tropism {
  double direction[3] = {0, 0, -1};
  double strength = 0;
};

/// The grammar's default layout (docs/design.md "Layout"); absent keys keep the command-line defaults.
struct StandSpec {
  std::optional<int> rows, per_row;
  std::optional<double> row_spacing, plant_spacing, double_rows, jitter;
  std::optional<bool> random_rotation;
  std::optional<std::uint64_t> seed;
  std::optional<std::string> positions;
  /// Where each key was given in the grammar file (key -> "FILE:LINE:COL"; empty for the command line's).
  std::map<std::string, std::string> where;
};

struct Grammar {
  std::string file;
  std::string name;
  std::uint64_t seed = 1;
  int steps = 0;
  double angle = 90;                                      // degrees
  double step = 1;                                        // metres
  std::vector<std::pair<std::string, double>> constants;  // after --set overrides
  SymbolTable symbols;
  std::vector<std::string> multi_char_names;  // declared names of several characters, longest first
  std::vector<SuccessorModule> axiom;
  RuleTable productions;
  RuleTable interpretation;
  std::vector<char> ignored;  // per symbol
  std::map<Symbol, OrganEntry> organs;
  int compound_leaf = -1;
  std::optional<Tropism> tropism;
  std::optional<StandSpec> stand;
  /// What the grammar allows but is likely a mistake, located ("FILE:LINE:COL: ..."): an organ
  /// that neither the axiom nor any rule writes. The commands print them as notes.
  std::vector<std::string> notes;

  /// The value of constant `name`, if the grammar has it.
  std::optional<double> constant(const std::string& name) const;
};

/// A constant override from the command line, `--set NAME=VALUE`.
struct ConstantOverride {
  std::string name;
  double value = 0;
};
/// Parses "NAME=VALUE"; throws std::invalid_argument naming the option on a bad one.
ConstantOverride parse_override(const std::string& text);

struct LoadOptions {
  std::vector<ConstantOverride> overrides;
};

/// FNV-1a over the grammar file's YAML document as parsed, in one canonical form: the same for
/// files that differ only in comments, blank lines, indentation, quoting or block/flow style,
/// different for any other change (a resumed sweep compares it). Throws GrammarError on malformed YAML.
std::string grammar_digest(const std::string& path);
/// FNV-1a over the file's bytes: what sweeps of canopy before grammar_digest kept.
std::string grammar_text_digest(const std::string& path);

/// Reads and compiles a grammar file; throws GrammarError (file, line, column) on any problem.
Grammar load_grammar(const std::string& path, const LoadOptions& options = {});
/// The same from text; `file` names it in errors.
Grammar parse_grammar(const std::string& yaml_text, const std::string& file, const LoadOptions& options = {});

}  // namespace canopy
