#pragma once
/// Printing derived strings in the grammar's own notation, and counting their modules.
#include "lsystem/grammar.hpp"
#include "lsystem/module_string.hpp"

#include <cstdio>
#include <string>
#include <vector>

namespace canopy {

/// Writes `s` as the grammar writes modules: names back to back, parameters as `(a,b)` in
/// shortest round-trip form; a space only where two names would otherwise read as a longer
/// declared name, so the text lexes back to the same modules.
void write_modules(std::FILE* out, const Grammar& g, const ModuleString& s);
std::string format_modules(const Grammar& g, const ModuleString& s);

/// Shortest text that reads back as exactly `v` (std::to_chars).
std::string format_number(double v);

/// Modules per symbol (brackets included), indexed by symbol id.
std::vector<std::size_t> count_modules(const Grammar& g, const ModuleString& s);
/// `{"modules": N, "counts": {"F": n, ...}}`, names sorted, only symbols that occur.
std::string stats_json(const Grammar& g, const ModuleString& s);

}  // namespace canopy
