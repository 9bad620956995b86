// Shared pieces of the canopy subcommands.
#include "tools/cli_common.hpp"

namespace canopy::cli {

bool any_row_option(const StandSpec& s) {
  return s.rows || s.per_row || s.row_spacing || s.plant_spacing || s.double_rows || s.jitter || s.random_rotation || s.seed;
}

/// A row layout from a stand entry (the grammar's or the command line's); unset keys take
/// DESIGN.md's defaults: 1 x 1 plants, 1.0 m rows, 0.4 m in the row, no jitter, no rotation, seed 1.
RowLayout to_row_layout(const StandSpec& s) {
  RowLayout l;
  l.rows = s.rows.value_or(1);
  l.per_row = s.per_row.value_or(1);
  l.row_spacing = s.row_spacing.value_or(1.0);
  l.plant_spacing = s.plant_spacing.value_or(0.4);
  l.double_rows = s.double_rows;
  l.jitter = s.jitter.value_or(0);
  l.random_rotation = s.random_rotation.value_or(false);
  l.seed = s.seed.value_or(1);
  return l;
}

GrowRequest grow_request(const std::string& grammar, const std::vector<std::string>& set, std::optional<int> steps, int lod,
                         int threads, std::size_t max_modules) {
  GrowRequest req;
  req.grammar = grammar;
  for (const auto& s : set) req.load.overrides.push_back(parse_override(s));
  req.steps = steps;
  req.lod = lod;
  req.threads = threads;
  req.max_modules = max_modules;
  return req;
}

}  // namespace canopy::cli
