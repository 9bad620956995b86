#pragma once
/// Derivation: parallel rewriting of the module string (ABOP ch. 1), with context matching that
/// skips branches (ABOP §1.8) and stochastic groups drawn from the plant's own seeded stream.
#include "geometry/layout.hpp"
#include "lsystem/grammar.hpp"
#include "lsystem/module_string.hpp"
#include "lsystem/rng.hpp"

#include <cstdint>
#include <optional>

namespace canopy {

/// Default module cap: 40 M modules (and kParamsPerModule parameters per module of the cap) keeps
/// two strings, their parameters and the context arrays of a derivation under about 2 GB.
inline constexpr std::size_t kDefaultMaxModules = 40'000'000;
/// The module cap bounds the parameters too: a string may hold this many per module of the cap,
/// so that modules of a thousand parameters count as the memory they take (the tomato grammars'
/// strings hold 1.1-1.7 parameters per module, derived or interpreted).
inline constexpr std::size_t kParamsPerModule = 2;

struct DeriveRequest {
  std::optional<int> steps;           // default: the grammar's `steps`; 0..kMaxSteps
  std::optional<std::uint64_t> seed;  // default: the grammar's `seed`
  std::size_t max_modules = kDefaultMaxModules;
};

/// The string after `steps` rewriting steps, before interpretation. Throws ModuleCapError when the
/// string would exceed the cap, GrammarError when an expression fails and std::invalid_argument
/// for steps outside 0..kMaxSteps.
ModuleString derive(const Grammar& g, const DeriveRequest& request = {});

/// The interpretation (homomorphism) applied once to a derived string, as the turtle sees it.
/// It draws from a second stream of the same seed, so it never shifts the derivation's draws.
ModuleString interpret(const Grammar& g, const ModuleString& derived, std::uint64_t seed,
                       std::size_t max_modules = kDefaultMaxModules);

/// Where module `module` of the string derive(g, req) gives (after interpretation when
/// `interpreted`) was written in the grammar file: the axiom's or a successor's module, or the
/// expression of its parameter `parameter` (0-based; -1: the module itself). Derives again while
/// tracking every module, so it is for messages about a string already derived; nothing when the
/// place is unknown.
std::optional<SourcePos> module_source(const Grammar& g, const DeriveRequest& req, bool interpreted,
                                       std::size_t module, int parameter = -1);

/// One parallel rewriting step of `in` by `table` into `out`. Past `max_modules` it throws
/// ModuleCapError naming the production that passed the cap and `step` (the derivation's step;
/// -1 for the interpretation).
void rewrite(const Grammar& g, const RuleTable& table, const ModuleString& in, ModuleString& out, Rng& rng,
             std::size_t max_modules, int step = 0);

/// Context neighbours (ABOP §1.8): for each module, the nearest preceding module on its path to
/// the root and the next module on the same axis, skipping whole branches and ignored names; -1
/// where there is none. Also each module's offset into the parameter array.
struct ContextIndex {
  PodBuffer<std::int32_t> left, right;
  PodBuffer<std::uint32_t> param_offset;
  void build(const Grammar& g, const ModuleString& s);
};

}  // namespace canopy
