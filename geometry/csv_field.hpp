#pragma once
/// One field of a CSV line as RFC 4180 writes it (quoted, quotes doubled, where it holds a comma,
/// a quote or a line break) and a line split back into its fields: the free-text cells of canopy's
/// tables (a sweep's messages in runs.csv, a grammar's path in plants.csv).
#include <string>
#include <vector>

namespace canopy {

/// `s` as one field: as it is, or quoted where it holds a comma, quote or newline (a newline is
/// written as a space: a row stays one line).
std::string csv_field(const std::string& s);

/// Splits one CSV line into `out` (quoted fields with doubled quotes); false when a quote is left
/// open.
bool split_csv(const std::string& line, std::vector<std::string>& out);

}  // namespace canopy
