// Shared pieces of the canopy subcommands.
#include "tools/cli_common.hpp"

#include "geometry/thread_limit.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <map>

namespace canopy::cli {

std::optional<double> finite_number(const std::string& in) {
  double v = 0;
  if (!CLI::detail::lexical_cast(in, v) || !std::isfinite(v) || in.find_first_of("xX") != std::string::npos)
    return std::nullopt;
  return v;
}

CLI::Validator whole_in(long long lo, long long hi) {
  return CLI::Validator(
      [lo, hi](std::string& in) {
        if (in.empty()) return std::string("needs a value, got an empty one");  // not 0 (--steps "")
        // Decimal only, rewritten in canonical form: CLI11 reads a leading 0 as octal ("010" was
        // 8 plants) and takes 0x; digits alone are read exactly (as a double, numbers near 2^63
        // rounded past the bound).
        const char* first = in.data() + (in.starts_with('+') ? 1 : 0);
        const char* end = in.data() + in.size();
        long long whole = 0;
        if (const auto [at, ec] = std::from_chars(first, end, whole); ec == std::errc() && at == end) {
          if (whole < lo || whole > hi)
            return fmt::format("needs a whole number from {} to {}, got {}", lo, hi, in);
          in = fmt::format("{}", whole);
          return std::string();
        }
        std::optional<double> v;
        // (An empty word fails with ptr == end: the error is what tells it apart, else "" was 0.)
        if (double d = 0;
            std::from_chars(first, end, d) == std::from_chars_result{end, std::errc()} && std::isfinite(d))
          v = d;
        // 2^63 and up do not fit a long long, though INT64_MAX as a double rounds up to 2^63.
        if (!v || *v != std::floor(*v) || *v < static_cast<double>(lo) || *v > static_cast<double>(hi) ||
            *v >= 0x1p63)
          return fmt::format("needs a whole number from {} to {}, got {}", lo, hi, in);
        in = fmt::format("{}", static_cast<long long>(*v));
        return std::string();
      },
      fmt::format("{}..{}", lo, hi), "whole number");
}

CLI::Validator at_least(double lo) {
  return CLI::Validator(
      [lo](std::string& in) {
        const auto v = finite_number(in);
        return v && *v >= lo ? std::string()
                             : fmt::format("needs a finite number of at least {}, got {}", lo, in);
      },
      "", "at least");
}

CLI::Validator above(double lo) {
  return CLI::Validator(
      [lo](std::string& in) {
        const auto v = finite_number(in);
        return v && *v > lo ? std::string()
                            : fmt::format("needs a finite number greater than {}, got {}", lo, in);
      },
      "", "above");
}

CLI::Validator number_in(double lo, double hi) {
  return CLI::Validator(
      [lo, hi](std::string& in) {
        const auto v = finite_number(in);
        return v && *v >= lo && *v <= hi ? std::string()
                                         : fmt::format("needs a number from {} to {}, got {}", lo, hi, in);
      },
      fmt::format("{}..{}", lo, hi), "number in");
}

CLI::Validator thread_count() { return whole_in(0, max_threads()); }

void one_value_per_use(CLI::App& app) {
  for (CLI::Option* o : app.get_options())
    if (!o->get_positional() && o->get_expected_max() > 1) o->allow_extra_args(false);
  for (CLI::App* sub : app.get_subcommands({})) one_value_per_use(*sub);
}

void print_notes(const std::vector<std::string>& notes) {
  for (const std::string& n : notes) std::fprintf(stderr, "canopy: note: %s\n", n.c_str());
}

void refuse_empty_values(CLI::App& app) {
  for (CLI::Option* o : app.get_options())
    if (o->get_expected_max() > 0)  // not a flag
      o->check(CLI::Validator(
          [](std::string& in) {
            return in.empty() ? std::string("needs a value, got an empty one") : std::string();
          },
          "", "not empty"));
  for (CLI::App* sub : app.get_subcommands({})) refuse_empty_values(*sub);
}

std::string parse_error_line(const CLI::Error& e) {
  std::string m = e.what();
  for (char& c : m)
    if (c == '\n' || c == '\r') c = ' ';
  while (!m.empty() && m.back() == ' ') m.pop_back();
  return "canopy: error: " + m;
}

bool any_row_option(const StandSpec& s) {
  return s.rows || s.per_row || s.row_spacing || s.plant_spacing || s.double_rows || s.jitter ||
         s.random_rotation || s.seed;
}

/// A row layout from a stand entry (the grammar's or the command line's); unset keys take
/// docs/design.md's defaults: 1 x 1 plants, 1.0 m rows, 0.4 m in the row, no jitter, no rotation, seed 1.
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

LayoutChoice choose_layout(const StandSpec& given, const std::optional<StandSpec>& grammar) {
  const StandSpec none;
  const StandSpec& g = grammar ? *grammar : none;
  StandSpec merged;
  LayoutChoice out;
  // One field: the command line's, else the grammar's; its source named either way.
  std::map<std::string, std::string> from_grammar;  // by option name: the stand entry's place
  const auto take = [&](const char* name, auto member) {
    const auto& mine = given.*member;
    const auto& theirs = g.*member;
    merged.*member = mine ? mine : theirs;
    out.sources.emplace_back(name, mine ? "command line" : theirs ? "grammar" : "default");
    if (!mine && theirs) {
      std::string option = std::string("--") + name;
      std::replace(option.begin(), option.end(), '_', '-');
      const auto it = g.where.find(name);
      from_grammar[option] = it != g.where.end() ? it->second : "the grammar's stand entry";
    }
  };
  take("rows", &StandSpec::rows);
  take("per_row", &StandSpec::per_row);
  take("row_spacing", &StandSpec::row_spacing);
  take("plant_spacing", &StandSpec::plant_spacing);
  take("double_rows", &StandSpec::double_rows);
  take("jitter", &StandSpec::jitter);
  take("random_rotation", &StandSpec::random_rotation);
  take("seed", &StandSpec::seed);
  out.layout = to_row_layout(merged);
  out.layout.from_grammar = std::move(from_grammar);
  return out;
}

std::string layout_line(const RowLayout& l, const LayoutSources& sources) {
  const std::string values[] = {std::to_string(l.rows),
                                std::to_string(l.per_row),
                                fmt::format("{} m", l.row_spacing),
                                fmt::format("{} m", l.plant_spacing),
                                l.double_rows ? fmt::format("{} m", *l.double_rows) : "none",
                                fmt::format("{} m", l.jitter),
                                l.random_rotation ? "yes" : "no",
                                std::to_string(l.seed)};
  std::string line = "layout:";
  for (std::size_t i = 0; i < sources.size(); ++i)
    line += fmt::format("{} {} {} ({})", i ? "," : "", sources[i].first, values[i], sources[i].second);
  return line;
}

GrowRequest grow_request(const std::string& grammar, const std::vector<std::string>& set,
                         std::optional<int> steps, int lod, int threads, std::size_t max_modules) {
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
