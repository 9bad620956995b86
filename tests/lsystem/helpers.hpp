#pragma once
// Small helpers shared by the lsystem suites.
#include "lsystem/derive.hpp"
#include "lsystem/grammar.hpp"
#include "lsystem/module_format.hpp"

#include <doctest/doctest.h>

#include <string>

namespace canopy::test {

inline Grammar grammar(const std::string& yaml, const LoadOptions& o = {}) {
  return parse_grammar(yaml, "test.yaml", o);
}

inline std::string derived(const Grammar& g, int steps, std::uint64_t seed = 1) {
  return format_modules(g, derive(g, DeriveRequest{steps, seed, kDefaultMaxModules}));
}

inline std::string source(const std::string& relative) {
  return std::string(CANOPY_SOURCE_DIR) + "/" + relative;
}

/// The error message of what `f` throws as a GrammarError ("" when it throws nothing).
template <typename F>
std::string grammar_error(F&& f) {
  try {
    f();
  } catch (const GrammarError& e) {
    return e.what();
  }
  return "";
}

}  // namespace canopy::test
