#pragma once
/// Shared pieces of the canopy subcommands.
#include "geometry/layout.hpp"
#include "lsystem/grammar.hpp"
#include "lsystem/grow.hpp"

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace canopy::cli {

/// `in` as a finite decimal number, or nothing (strtod also reads hexadecimal: "0x1p-4").
std::optional<double> finite_number(const std::string& in);

/// CLI11's number checks (NonNegativeNumber, Range, ...) compare, and every comparison with NaN
/// is false, so they let "nan" through: options taking a real number add this check first.
inline const CLI::Validator kFinite(
    [](std::string& in) { return finite_number(in) ? std::string() : "needs a finite number, got " + in; },
    "", "finite");

/// A seed: a whole number in [0, 2^64). CLI11 reads an unsigned option with strtoull, which takes
/// "-1" and "18446744073709551616" to 2^64 - 1 without a word, and a leading 0 as octal: the
/// value is rewritten in decimal (register with ->transform()).
inline const CLI::Validator kSeed(
    [](std::string& in) {
      std::string error;
      if (const auto seed = parse_seed(in)) in = std::to_string(*seed);
      else error.append("needs a whole number from 0 to 18446744073709551615, got ").append(in);
      return error;
    },
    "", "seed");

/// Range checks that say their bounds as written: CLI11's Range prints them with std::to_string,
/// so NonNegativeNumber's upper bound came out as a 309-digit number. A whole-number check also
/// rewrites the value as an integer, so `--steps 1e3` reads as 1000 rather than failing to convert:
/// register it with ->transform() (->check() hands validators a copy).
CLI::Validator whole_in(long long lo, long long hi);
/// A finite number of at least `lo`.
CLI::Validator at_least(double lo);
/// A finite number greater than `lo`.
CLI::Validator above(double lo);
/// A finite number from `lo` to `hi`.
CLI::Validator number_in(double lo, double hi);
/// --threads: 0 (all cores) up to canopy's maximum (geometry/thread_limit.hpp).
CLI::Validator thread_count();

/// The one-line form of a command-line parse error: `canopy: error: ...` (CLI11's own text, its
/// line breaks joined, without the "Run with --help" line).
std::string parse_error_line(const CLI::Error& e);
/// Every repeatable option (`--set`, `--sun`, ...) of `app` and its subcommands takes one value
/// each time it is given: CLI11 let a list option take the words after it, so `canopy derive
/// --set r=2 GRAMMAR` took the grammar as a second --set and refused the command.
void one_value_per_use(CLI::App& app);
/// No option or argument of `app` and its subcommands takes an empty value: `detect --csv ""`
/// wrote nothing and exited 0, `stand --positions ""` grew the grammar's layout instead, an empty
/// folder or file name failed late with an unclear message.
void refuse_empty_values(CLI::App& app);

/// A distance in metres that is rarely meant above 0.1 m (a clearance): a larger value runs as
/// asked, with a note on stderr saying what it means, since millimetres typed where metres are
/// read (`--clearance 0.5` for half a millimetre) make most organ pairs of a stand a contact.
inline CLI::Validator metres_note(std::string option) {
  return CLI::Validator(
      [option](std::string& in) {
        double v = 0;
        if (CLI::detail::lexical_cast(in, v) && std::isfinite(v) && v >= 0.1)
          std::fprintf(stderr, "canopy: note: %s is in metres: %s is %g mm (for %g mm write %g)\n",
                       option.c_str(), in.c_str(), v * 1000, v, v / 1000);
        return std::string();
      },
      "", "metres");
}

/// A grammar's notes (Grammar::notes) on standard error, one "canopy: note: ..." line each.
void print_notes(const std::vector<std::string>& notes);

/// A subcommand: registers its options on `app` and returns what runs it after parsing.
struct Command {
  CLI::App* app = nullptr;
  std::function<int()> run;
};

Command add_derive(CLI::App& root);
Command add_info(CLI::App& root);
Command add_stand(CLI::App& root);
Command add_detect(CLI::App& root);
Command add_sweep(CLI::App& root);
Command add_render(CLI::App& root);
Command add_light(CLI::App& root);

/// Whether any row option is set in a stand entry.
bool any_row_option(const StandSpec& s);
/// A row layout from a stand entry (the grammar's or the command line's); unset keys take
/// docs/design.md's defaults: 1 x 1 plants, 1.0 m rows, 0.4 m in the row, no jitter, no rotation, seed 1.
RowLayout to_row_layout(const StandSpec& s);

/// Per field of a row layout, in RowLayout's order (rows, per_row, row_spacing, plant_spacing,
/// double_rows, jitter, random_rotation, seed), where its value came from: "command line",
/// "grammar" or "default".
using LayoutSources = std::vector<std::pair<std::string, std::string>>;
/// The row layout a run uses and where each of its values came from.
struct LayoutChoice {
  RowLayout layout;
  LayoutSources sources;
};
/// The layout options override the grammar's stand entry field by field, not as a whole
/// (docs/design.md "Layout"): each field is the command line's where it gives one, else the grammar
/// entry's, else to_row_layout's default. `--rows 100 --per-row 100` keeps the entry's spacing,
/// rotation, jitter and seed. `given` comes from the command line (or the Python module's keyword
/// arguments, named "command line" too).
LayoutChoice choose_layout(const StandSpec& given, const std::optional<StandSpec>& grammar);
/// One line for the terminal: "layout: 10 x 100 plants (rows, per_row: command line), ...".
std::string layout_line(const RowLayout& layout, const LayoutSources& sources);
/// A grow request for `grammar` with the command line's --set, --steps, --lod, --threads and
/// --max-modules (plants still to be placed).
GrowRequest grow_request(const std::string& grammar, const std::vector<std::string>& set,
                         std::optional<int> steps, int lod, int threads, std::size_t max_modules);

}  // namespace canopy::cli
