#pragma once
/// What `canopy sweep` varies: plant spacings (or densities), row spacings and ages, each a list
/// `a,b,c` or a range `start:stop:step` (stop included), with several seeds per cell.
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace canopy::cli {

/// The number at the start of `s` (std::stod without exceptions): how many characters it took
/// in `used` (0 when there is none).
double leading_number(const std::string& s, std::size_t& used);
/// "a,b" -> {a, b} (--sun's ELEVATION,AZIMUTH), both finite; throws std::invalid_argument naming
/// `option`.
std::pair<double, double> number_pair(const std::string& option, const std::string& text);

/// Parses a list or range of numbers for option `name`; throws std::invalid_argument naming the
/// option on an empty list, a bad number, a zero or backward step, or a value below `min`
/// (strictly below when `strict`).
std::vector<double> parse_number_list(const std::string& name, const std::string& text, double min,
                                      bool strict);

struct SweepCell {
  double plant_spacing = 0.4, row_spacing = 1.0;
  double density = 0;  // plants per m2
  std::optional<int> steps;
};

/// The cells in run order: row spacing, then plant spacing (or density), then age.
std::vector<SweepCell> sweep_cells(const std::vector<double>& row_spacings,
                                   const std::vector<double>& plant_spacings,
                                   const std::vector<double>& densities,
                                   const std::vector<std::optional<int>>& steps);

}  // namespace canopy::cli
