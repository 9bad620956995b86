#include "geometry/layout.hpp"

#include "geometry/input_file.hpp"
#include "geometry/mix64.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <map>
#include <numbers>
#include <stdexcept>

namespace canopy {
namespace {

/// A small stream for jitter and rotation draws (splitmix64), apart from the plants' own.
struct LayoutStream {
  std::uint64_t state;
  double uniform() { return static_cast<double>(mix64(state++) >> 11) * 0x1.0p-53; }
};

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

/// Why a positions file's grammar cell may not be read without --any-grammar-path, or nullptr:
/// an absolute path, one whose '..' climbs above the positions file's folder (both read from the
/// text alone), or one that leads out of that folder (`base`, resolved) through a symbolic link.
const char* grammar_cell_refusal(std::string_view cell, const std::filesystem::path& base) {
  namespace fs = std::filesystem;
  const fs::path p{std::string(cell)};
  if (p.is_absolute() || p.has_root_name() || p.has_root_directory()) return "is an absolute path";
  int depth = 0;
  for (const auto& part : p) {
    if (part == "..") {
      if (--depth < 0) return "leaves the positions file's folder";
    } else if (part != "." && !part.empty()) {
      ++depth;
    }
  }
  // Written inside the folder, it may still lead out of it through a symbolic link (a folder
  // `link -> /elsewhere`): the path the kernel follows must stay in the folder (`base`, resolved).
  if (base.empty()) return nullptr;
  std::error_code ec;
  const fs::path target = fs::weakly_canonical(base / p, ec);
  if (ec) return nullptr;
  const auto rel = target.lexically_relative(base);
  if (rel.empty() || *rel.begin() == "..")
    return "leads out of the positions file's folder through a symbolic link";
  return nullptr;
}

/// One line's cells as RFC 4180 writes them (a cell in double quotes may hold commas, and "" in it
/// is a quote; canopy's plants.csv quotes a grammar path so), white space around a cell outside
/// its quotes dropped; each with the column it begins at (1-based). `open_quote` is set to the
/// column of a quote left open (0 when none).
std::vector<std::pair<std::string, int>> split(std::string_view line, int& open_quote) {
  std::vector<std::pair<std::string, int>> cells;
  open_quote = 0;
  std::size_t i = 0;
  for (;;) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const int column = static_cast<int>(i) + 1;
    std::string cell;
    if (i < line.size() && line[i] == '"') {
      const std::size_t quote = i++;
      bool closed = false;
      for (; i < line.size(); ++i) {
        if (line[i] != '"') cell += line[i];
        else if (i + 1 < line.size() && line[i + 1] == '"') cell += '"', ++i;
        else {
          closed = true;
          ++i;
          break;
        }
      }
      if (!closed) open_quote = static_cast<int>(quote) + 1;
      const std::size_t end = std::min(line.find(',', i), line.size());
      cell += std::string(trim(line.substr(i, end - i)));  // text after the closing quote, as it is
      i = end;
    } else {
      const std::size_t end = std::min(line.find(',', i), line.size());
      cell = std::string(trim(line.substr(i, end - i)));
      i = end;
    }
    cells.emplace_back(std::move(cell), column);
    if (i >= line.size()) break;
    ++i;  // the comma
  }
  return cells;
}

/// How a refusal names a layout field: its option, or the grammar's stand entry key it came from.
std::string field(const RowLayout& l, const std::string& option) {
  if (!l.from_grammar.count(option)) return option;
  std::string key = option.substr(2);
  std::replace(key.begin(), key.end(), '-', '_');
  return "the stand entry's " + key;
}

/// "FILE:LINE:COL: " of the first of `options` a grammar's stand entry gave (nothing if none did).
std::string place(const RowLayout& l, std::initializer_list<std::string> options) {
  for (const std::string& o : options)
    if (const auto it = l.from_grammar.find(o); it != l.from_grammar.end()) return it->second + ": ";
  return "";
}

/// " (+ --jitter J m)" where there is jitter.
std::string jitter_part(const RowLayout& l) {
  return l.jitter > 0 ? fmt::format(" (+ {} {:g} m)", field(l, "--jitter"), l.jitter) : "";
}

}  // namespace

void check_reach(const RowLayout& l) {
  const std::pair<const char*, double> options[] = {{"--plant-spacing", l.plant_spacing},
                                                    {"--row-spacing", l.row_spacing},
                                                    {"--double-rows", l.double_rows.value_or(0)},
                                                    {"--jitter", l.jitter}};
  for (const auto& [name, v] : options)
    if (v > kMaxPlantCoordinate)
      throw std::invalid_argument(fmt::format("{}{} {:g} m: plants may stand at most {:g} m from the origin",
                                              place(l, {name}), field(l, name), v, kMaxPlantCoordinate));
  const double x = (l.per_row - 1) * l.plant_spacing + l.jitter;
  if (x > kMaxPlantCoordinate)
    throw std::invalid_argument(fmt::format(
        "{}{} {} x {} {:g} m{} reaches x = {:.10g} m: plants may stand at most {:g} m from the origin",
        place(l, {"--per-row", "--plant-spacing", "--jitter"}), field(l, "--per-row"), l.per_row,
        field(l, "--plant-spacing"), l.plant_spacing, jitter_part(l), x, kMaxPlantCoordinate));
  // The farthest row: the last, or with double rows the farther of the last two.
  double y = l.double_rows ? 0.0 : (l.rows - 1) * l.row_spacing;
  if (l.double_rows)
    for (int r = std::max(0, l.rows - 2); r < l.rows; ++r)
      y = std::max(y, (r / 2) * l.row_spacing + (r % 2) * *l.double_rows);
  if (y + l.jitter > kMaxPlantCoordinate)
    throw std::invalid_argument(fmt::format(
        "{}{} {} x {} {:g} m{}{} reaches y = {:.10g} m: plants may stand at most {:g} m from the origin",
        place(l, {"--rows", "--row-spacing", "--double-rows", "--jitter"}), field(l, "--rows"), l.rows,
        field(l, "--row-spacing"), l.row_spacing,
        l.double_rows ? fmt::format(" with {} {:g} m", field(l, "--double-rows"), *l.double_rows) : "",
        jitter_part(l), y + l.jitter, kMaxPlantCoordinate));
}

std::uint64_t plant_seed(std::uint64_t stand_seed, std::uint64_t plant) {
  return mix64(mix64(stand_seed) ^ (plant * 0xd1b54a32d192ed03ULL)) >>
         1;  // 63 bits: prints as a plain number
}

std::optional<std::uint64_t> parse_seed(std::string_view text) {
  std::uint64_t v = 0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || r.ec != std::errc() || r.ptr != text.data() + text.size()) return std::nullopt;
  return v;
}

std::vector<PlantPlacement> row_layout(const RowLayout& l) {
  if (l.rows < 1 || l.per_row < 1)
    throw std::invalid_argument(
        fmt::format("--rows and --per-row must be at least 1 (got {} and {})", l.rows, l.per_row));
  // Each named: an infinite jitter used to surface as plant 0's position not being finite.
  const std::pair<const char*, double> lengths[] = {{"row spacing", l.row_spacing},
                                                    {"plant spacing", l.plant_spacing},
                                                    {"double-row gap", l.double_rows.value_or(0)},
                                                    {"jitter", l.jitter}};
  for (const auto& [name, v] : lengths)
    if (!(v >= 0) || !std::isfinite(v))
      throw std::invalid_argument(
          fmt::format("the {} must be a finite number of metres, not negative (got {})", name, v));
  // A pair's second row lies between its first and the next pair's (periodic light repeats even a
  // single pair every row spacing): a gap of 0, or of the row spacing or more, stacked rows on one
  // line or put them out of order, without a word.
  if (l.double_rows && (*l.double_rows <= 0 || *l.double_rows >= l.row_spacing))
    throw std::invalid_argument(fmt::format(
        "{}double rows {:g} m apart ({}): the two rows of a pair must be more than 0 m and less than the "
        "row spacing ({:g} m{}, from pair to pair) apart",
        place(l, {"--double-rows", "--row-spacing"}), *l.double_rows, field(l, "--double-rows"),
        l.row_spacing, l.from_grammar.count("--row-spacing") ? ", the stand entry's row_spacing" : ""));
  check_reach(l);
  std::vector<PlantPlacement> out;
  out.reserve(static_cast<std::size_t>(l.rows) * static_cast<std::size_t>(l.per_row));
  LayoutStream rng{mix64(l.seed ^ 0x6c61796f7574ULL)};
  for (int r = 0; r < l.rows; ++r) {
    const double y = l.double_rows ? (r / 2) * l.row_spacing + (r % 2) * *l.double_rows : r * l.row_spacing;
    for (int k = 0; k < l.per_row; ++k) {
      PlantPlacement p;
      p.x = k * l.plant_spacing;
      p.y = y;
      if (l.jitter > 0) {
        const double rad = l.jitter * std::sqrt(rng.uniform());
        const double a = 2 * std::numbers::pi * rng.uniform();
        p.x += rad * std::cos(a);
        p.y += rad * std::sin(a);
      }
      if (l.random_rotation) p.rotation_deg = 360 * rng.uniform();
      p.seed = plant_seed(l.seed, out.size());
      out.push_back(p);
    }
  }
  return out;
}

std::vector<PlantPlacement> default_stand_layout(int plants) {
  RowLayout l;
  l.per_row = std::max(1, std::min(plants, 100));
  l.rows = std::max(1, (plants + l.per_row - 1) / l.per_row);
  l.row_spacing = 1.0;
  l.plant_spacing = 0.4;
  l.random_rotation = true;
  l.jitter = 0.02;
  l.seed = 1;
  auto p = row_layout(l);
  p.resize(static_cast<std::size_t>(std::max(0, plants)));
  return p;
}

std::vector<PlantPlacement> read_positions(const std::string& path, bool any_grammar_path) {
  InputFile in(path, "positions file", kMaxPositionsBytes);
  std::filesystem::path base;  // the positions file's folder, resolved (grammar cells stay in it)
  bool base_resolved = false;
  std::map<std::string, const char*> verdicts;  // grammar cell -> its refusal (null: taken)
  std::string line;
  std::map<std::string, int> col;
  std::vector<PlantPlacement> out;
  std::size_t ncols = 0;
  while (in.next_line(line)) {
    const int line_no = in.line_number();
    // A spreadsheet's "CSV UTF-8" export starts with a byte-order mark: not part of the header.
    if (line_no == 1 && line.starts_with("\xEF\xBB\xBF")) line.erase(0, 3);
    if (trim(line).empty() || trim(line)[0] == '#') continue;
    int open_quote = 0;
    const auto cells = split(line, open_quote);
    if (open_quote)
      throw std::invalid_argument(
          fmt::format("{}:{}:{}: a quoted cell is not closed (a quote inside one is written \"\")", path,
                      line_no, open_quote));
    if (col.empty()) {
      for (std::size_t i = 0; i < cells.size(); ++i)
        col.emplace(std::string(cells[i].first), static_cast<int>(i));
      for (const char* need : {"x", "y", "rotation", "seed"})
        if (!col.count(need)) {
          // A spreadsheet set to a decimal comma separates its "CSV" cells with ';'.
          const bool other_separator =
              cells.size() == 1 && cells[0].first.find_first_of(";\t") != std::string::npos;
          throw std::invalid_argument(fmt::format(
              "{}:{}: missing column '{}' (the header needs x,y,rotation,seed and may add grammar,steps){}",
              path, line_no, need,
              other_separator ? "; the cells are separated by ';' or tabs, and positions files use commas"
                              : ""));
        }
      // A misspelt column ("Steps") would otherwise be passed over and its values never used.
      for (std::size_t i = 0; i < cells.size(); ++i) {
        const auto& [name, column] = cells[i];
        const std::size_t first = static_cast<std::size_t>(col.at(std::string(name)));
        if (first != i)
          throw std::invalid_argument(
              fmt::format("{}:{}:{}: column '{}' appears twice in the header (cells {} and {})", path,
                          line_no, column, name, first + 1, i + 1));
        if (name != "x" && name != "y" && name != "rotation" && name != "seed" && name != "grammar" &&
            name != "steps")
          throw std::invalid_argument(fmt::format(
              "{}:{}:{}: unknown column '{}' (the header has x,y,rotation,seed and may add grammar,steps)",
              path, line_no, column, name));
      }
      ncols = cells.size();
      continue;
    }
    if (cells.size() != ncols)
      throw std::invalid_argument(fmt::format("{}:{}: expected {} cells as in the header, got {}", path,
                                              line_no, ncols, cells.size()));
    auto number = [&](const char* name) {
      const auto& [cell, column] = cells[static_cast<std::size_t>(col[name])];
      double v = 0;
      const auto r = std::from_chars(cell.data(), cell.data() + cell.size(), v);
      const bool whole_cell = r.ptr == cell.data() + cell.size();
      if (!cell.empty() && whole_cell && r.ec == std::errc::result_out_of_range)
        throw std::invalid_argument(
            fmt::format("{}:{}:{}: column '{}' needs a finite number, got '{}', which is out of range", path,
                        line_no, column, name, cell));
      if (cell.empty() || r.ec != std::errc() || !whole_cell || !std::isfinite(v))
        throw std::invalid_argument(fmt::format("{}:{}:{}: column '{}' needs a finite number, got '{}'", path,
                                                line_no, column, name, cell));
      return v;
    };
    // A coordinate past the bound cannot be written faithfully or kept to the plant frame's precision.
    auto coordinate = [&](const char* name) {
      const double v = number(name);
      if (std::fabs(v) > kMaxPlantCoordinate) {
        const auto& [cell, column] = cells[static_cast<std::size_t>(col[name])];
        throw std::invalid_argument(
            fmt::format("{}:{}:{}: column '{}' is {} m: plants may stand at most {:g} m from the origin",
                        path, line_no, column, name, cell, kMaxPlantCoordinate));
      }
      return v;
    };
    PlantPlacement p;
    p.source_line = line_no;
    p.x = coordinate("x");
    p.y = coordinate("y");
    p.rotation_deg = number("rotation");
    {
      const auto& [cell, column] = cells[static_cast<std::size_t>(col["seed"])];
      const auto seed = parse_seed(cell);
      if (!seed)
        throw std::invalid_argument(fmt::format("{}:{}:{}: column 'seed' needs a whole number, got '{}'",
                                                path, line_no, column, cell));
      p.seed = *seed;
    }
    if (col.count("grammar")) {
      const auto& [cell, column] = cells[static_cast<std::size_t>(col["grammar"])];
      if (!any_grammar_path) {
        // The folder resolved once, and each distinct cell judged once (a 100,000-row file
        // resolved both paths on every row: 3.1 s instead of 0.4).
        if (!base_resolved) {
          std::error_code ec;
          const std::filesystem::path folder = std::filesystem::path(path).parent_path();
          base =
              std::filesystem::weakly_canonical(std::filesystem::absolute(folder.empty() ? "." : folder), ec);
          if (ec) base.clear();
          base_resolved = true;
        }
        auto judged = verdicts.find(cell);
        if (judged == verdicts.end()) judged = verdicts.emplace(cell, grammar_cell_refusal(cell, base)).first;
        if (const char* why = judged->second)
          throw std::invalid_argument(
              fmt::format("{}:{}:{}: column 'grammar': '{}' {}; a grammar cell names a file in the positions "
                          "file's folder or below it (--any-grammar-path allows others)",
                          path, line_no, column, cell, why));
      }
      p.grammar = std::string(cell);
    }
    if (col.count("steps") && !cells[static_cast<std::size_t>(col["steps"])].first.empty()) {
      const auto& [cell, column] = cells[static_cast<std::size_t>(col["steps"])];
      const double v = number("steps");
      if (v != std::floor(v) || v < 0 || v > kMaxSteps)
        throw std::invalid_argument(
            fmt::format("{}:{}:{}: column 'steps' needs a whole number from 0 to {}, got '{}'", path, line_no,
                        column, kMaxSteps, cell));
      p.steps = static_cast<int>(v);
    }
    out.push_back(p);
  }
  if (col.empty())
    throw std::invalid_argument(
        fmt::format("{}: empty positions file (expected a header x,y,rotation,seed)", path));
  return out;
}

}  // namespace canopy
