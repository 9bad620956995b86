#include "tools/sweep_spec.hpp"

#include "geometry/split_list.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace canopy::cli {
namespace {

/// A decimal number, as the other options take them (strtod also reads hexadecimal: 0x10 was
/// 16 plants' steps and a 16 m spacing).
double number(const std::string& name, const std::string& s) {
  std::size_t used = 0;
  const double v = leading_number(s, used);
  if (used == 0 || used != s.size() || !std::isfinite(v))
    throw std::invalid_argument(fmt::format("{}: '{}' is not a decimal number", name, s));
  return v;
}

}  // namespace

double leading_number(const std::string& s, std::size_t& used) {
  used = 0;
  try {
    const double v = std::stod(s, &used);
    // Decimal only, as every number canopy reads (strtod also takes "0x3c" and "0x1p-4").
    if (s.substr(0, used).find_first_of("xX") != std::string::npos) used = 0;
    return used ? v : 0;
  } catch (const std::exception&) {
    used = 0;
    return 0;
  }
}

std::pair<double, double> number_pair(const std::string& option, const std::string& text) {
  std::size_t used = 0;
  const double a = leading_number(text, used);
  if (used == 0 || used >= text.size() || text[used] != ',')
    throw std::invalid_argument(fmt::format("{}: '{}' is not ELEVATION,AZIMUTH", option, text));
  const std::string rest = text.substr(used + 1);
  std::size_t used2 = 0;
  const double b = leading_number(rest, used2);
  if (used2 == 0 || used2 != rest.size() || !std::isfinite(a) || !std::isfinite(b))
    throw std::invalid_argument(fmt::format("{}: '{}' is not ELEVATION,AZIMUTH", option, text));
  return {a, b};
}

std::vector<double> parse_number_list(const std::string& name, const std::string& text, double min,
                                      bool strict) {
  std::vector<double> out;
  if (text.find(':') != std::string::npos) {
    std::vector<std::string> part;
    std::size_t i = 0;
    for (std::size_t j; (j = text.find(':', i)) != std::string::npos; i = j + 1)
      part.push_back(text.substr(i, j - i));
    part.push_back(text.substr(i));
    if (part.size() != 3)
      throw std::invalid_argument(fmt::format("{}: a range is start:stop:step, got '{}'", name, text));
    const double a = number(name, part[0]), b = number(name, part[1]), step = number(name, part[2]);
    if (!(step > 0))
      throw std::invalid_argument(fmt::format("{}: the step of '{}' must be positive", name, text));
    if (b < a)
      throw std::invalid_argument(fmt::format("{}: the range '{}' is empty (stop below start)", name, text));
    // n + 1 values: start, then n steps (checked as a double, before a cast could overflow).
    const double last = std::floor((b - a) / step + 1e-9);
    if (!(last < 100000))
      throw std::invalid_argument(fmt::format("{}: the range '{}' has more than 100,000 values", name, text));
    const auto n = static_cast<long>(last);
    // start + k x step carries the step's rounding (0.1:0.5:0.1 made 0.30000000000000004): a
    // value after the start (which is as typed) is the double nearest its first 12 significant
    // digits where that moves it by less than a millionth of the step (so no two values of a
    // range ever merge).
    out.push_back(a);
    for (long k = 1; k <= n; ++k) {
      const double raw = a + static_cast<double>(k) * step;
      const double tidy = std::stod(fmt::format("{:.12g}", raw));
      out.push_back(std::abs(tidy - raw) < 1e-6 * step ? tidy : raw);
    }
  } else if (!text.empty()) {
    for (const std::string& item : split_list(text)) {
      if (item.empty()) throw std::invalid_argument(fmt::format("{}: empty item in '{}'", name, text));
      out.push_back(number(name, item));
    }
  }
  if (out.empty()) throw std::invalid_argument(fmt::format("{}: no values given", name));
  // A value given twice made its runs twice, and the summary pooled them as one cell.
  std::vector<double> sorted = out;
  std::sort(sorted.begin(), sorted.end());
  if (const auto twice = std::adjacent_find(sorted.begin(), sorted.end()); twice != sorted.end())
    throw std::invalid_argument(fmt::format("{}: {} is given twice in '{}'", name, *twice, text));
  for (double v : out)
    if (strict ? !(v > min) : !(v >= min))
      throw std::invalid_argument(
          fmt::format("{}: {} must be {} {}", name, v, strict ? "greater than" : "at least", min));
  return out;
}

std::vector<SweepCell> sweep_cells(const std::vector<double>& row_spacings,
                                   const std::vector<double>& plant_spacings,
                                   const std::vector<double>& densities,
                                   const std::vector<std::optional<int>>& steps) {
  std::vector<SweepCell> cells;
  for (double row : row_spacings) {
    std::vector<double> plant;
    if (!densities.empty())
      for (double d : densities) plant.push_back(1.0 / (d * row));
    else plant = plant_spacings;
    for (double p : plant)
      for (const auto& st : steps) {
        SweepCell c;
        c.plant_spacing = p;
        c.row_spacing = row;
        c.density = 1.0 / (p * row);
        c.steps = st;
        cells.push_back(c);
      }
  }
  return cells;
}

}  // namespace canopy::cli
