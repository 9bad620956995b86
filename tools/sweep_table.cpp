#include "tools/sweep_table.hpp"

#include "geometry/csv_field.hpp"

#include "geometry/input_file.hpp"
#include "geometry/atomic_file.hpp"
#include "geometry/write_all.hpp"

#include <fmt/format.h>
#include <cstring>
#include <cerrno>
#include <fcntl.h>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <optional>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

namespace canopy::cli {
namespace {

const std::vector<std::string> kKey{"plant_spacing", "row_spacing", "steps", "seed"};
const std::vector<std::string> kText{"status", "message"};

/// The columns summary.csv averages: every column but the run's key, status and text.
bool is_metric(const std::string& c) {
  return c != "run" && c != "seed" && c != "backend" && c != "plant_spacing" && c != "row_spacing" &&
         c != "steps" && c != "density" && c != "status" && c != "message";
}

/// A cell as a finite number, the whole cell.
std::optional<double> finite_number(const std::string& s) {
  double v = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || r.ec != std::errc() || r.ptr != s.data() + s.size() || !std::isfinite(v))
    return std::nullopt;
  return v;
}

std::string line_of(const RunRow& r) {
  std::string s;
  for (const std::string& c : run_columns()) {
    if (!s.empty()) s += ',';
    const auto it = r.find(c);
    s += csv_field(it == r.end() ? "" : it->second);
  }
  return s + "\n";
}

std::string header() {
  std::string s;
  for (const std::string& c : run_columns()) s += (s.empty() ? "" : ",") + c;
  return s + "\n";
}

}  // namespace

const std::vector<std::string>& run_columns() {
  static const std::vector<std::string> c{"run",
                                          "plant_spacing",
                                          "row_spacing",
                                          "density",
                                          "steps",
                                          "seed",
                                          "status",
                                          "plants",
                                          "organs",
                                          "lai",
                                          "lai_plants",
                                          "plant_between_per_plant",
                                          "plant_within_per_plant",
                                          "leaf_between_per_plant",
                                          "leaf_within_per_plant",
                                          "organ_between_per_plant",
                                          "organ_within_per_plant",
                                          "exact_between_per_plant",
                                          "exact_within_per_plant",
                                          "organs_turned",
                                          "organs_turned_per_plant",
                                          "mean_turn_deg",
                                          "max_turn_deg",
                                          "rounds",
                                          "residual_contacts",
                                          "ground_cover_before",
                                          "direct_before",
                                          "diffuse_before",
                                          "star_before",
                                          "mean_inclination_before",
                                          "light_se_before",
                                          "ground_cover_after",
                                          "direct_after",
                                          "diffuse_after",
                                          "star_after",
                                          "mean_inclination_after",
                                          "light_se_after",
                                          "generate_s",
                                          "detect_s",
                                          "resolve_s",
                                          "light_s",
                                          "backend",
                                          "message"};
  return c;
}

std::string run_key(const RunRow& r) {
  std::string k;
  for (const std::string& c : kKey) k += (k.empty() ? "" : "|") + (r.count(c) ? r.at(c) : "");
  return k;
}

std::vector<RunRow> read_runs(const std::string& path) {
  std::vector<RunRow> rows;
  if (!std::filesystem::exists(std::filesystem::symlink_status(path))) return rows;
  InputFile in(path, "sweep's runs.csv", kMaxRunsCsvBytes);
  in.keep_nul_bytes();  // a torn last line may be NULs; its columns tell it
  std::string line;
  if (!in.next_line(line)) return rows;
  if (line + "\n" != header())
    throw std::invalid_argument(
        fmt::format("{}: not a runs.csv of this canopy version (header differs); use another -o", path));
  std::vector<std::string> f;
  std::map<std::string, int> seen;  // run key -> its line
  int torn = 0;                     // a line that is not a whole row, dropped if it is the last
  while (in.next_line(line)) {
    if (torn)
      throw std::invalid_argument(fmt::format(
          "{}:{}: not a whole row of {} columns, and not the last line (a sweep that is killed tears "
          "only its last line); mend or delete that line, or use another -o",
          path, torn, run_columns().size()));
    if (!split_csv(line, f) || f.size() != run_columns().size()) {
      torn = in.line_number();
      continue;
    }
    RunRow r;
    for (std::size_t i = 0; i < f.size(); ++i) {
      const std::string& column = run_columns()[i];
      // summary.csv averages these: a value that is not a number is not from canopy sweep.
      if (is_metric(column) && !f[i].empty() && !finite_number(f[i]))
        throw std::invalid_argument(fmt::format(
            "{}:{}: column '{}' needs a number, got '{}' (not a runs.csv written by canopy sweep; "
            "use another -o)",
            path, in.line_number(), column, f[i]));
      // A resumed sweep reruns what failed and keeps what is ok: no third kind of run.
      if (column == "status" && f[i] != "ok" && f[i] != "failed")
        throw std::invalid_argument(fmt::format(
            "{}:{}: column 'status' needs 'ok' or 'failed', got '{}' (not a runs.csv written by canopy "
            "sweep; use another -o)",
            path, in.line_number(), f[i]));
      r[column] = f[i];
    }
    // A sweep writes each run once; a second row of a run was pooled in the summary as another.
    if (const auto [it, fresh] = seen.emplace(run_key(r), in.line_number()); !fresh)
      throw std::invalid_argument(fmt::format(
          "{}:{}: the run of line {} again (plant spacing {}, row spacing {}, steps {}, seed {}); "
          "delete one of the two lines, or use another -o",
          path, in.line_number(), it->second, r["plant_spacing"], r["row_spacing"], r["steps"], r["seed"]));
    rows.push_back(std::move(r));
  }
  return rows;
}

nlohmann::ordered_json read_sweep_settings(const std::string& path) {
  const std::string text = read_input_file(path, "sweep's settings", kMaxSweepJsonBytes);
  try {
    // Nesting is bounded while parsing: comparing and printing a parsed value recurse once per
    // level, and a file of 100,000 '[' would overflow the stack there.
    const auto bounded = [](int depth, nlohmann::ordered_json::parse_event_t, nlohmann::ordered_json&) {
      if (depth > 16) throw std::invalid_argument("nested more than 16 levels deep");
      return true;
    };
    nlohmann::ordered_json j = nlohmann::ordered_json::parse(text, bounded);
    if (!j.is_object()) throw std::invalid_argument("not a JSON object");
    return j;
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(fmt::format("{}: not a sweep's settings ({})", path, e.what()));
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(fmt::format("{}: not a sweep's settings ({})", path, e.what()));
  }
}

void write_runs(const std::string& path, const std::vector<RunRow>& rows) {
  AtomicFile out(path);  // synced and renamed into place: a kill leaves the earlier table whole
  std::string text = header();
  for (const RunRow& r : rows) text += line_of(r);
  out.write(text);
  out.commit();
}

void append_run(const std::string& path, const RunRow& row) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0666);
  if (fd < 0) throw std::runtime_error(fmt::format("cannot append to {}: {}", path, std::strerror(errno)));
  const off_t before = ::lseek(fd, 0, SEEK_END);
  const std::string l = line_of(row);
  int error = write_all(fd, l.data(), l.size());
  if (!error && ::fsync(fd) != 0) error = errno;
  // A row written in part (the disk filled) is cut off again: the table keeps whole rows only.
  if (error && before >= 0) (void)!::ftruncate(fd, before);
  ::close(fd);
  if (error) throw std::runtime_error(fmt::format("cannot append to {}: {}", path, std::strerror(error)));
}

std::string summary_csv(const std::vector<RunRow>& rows) {
  std::vector<std::string> metrics;
  for (const std::string& c : run_columns())
    if (is_metric(c)) metrics.push_back(c);
  struct Cell {
    RunRow first;
    std::size_t runs = 0, failed = 0;
    std::map<std::string, std::vector<double>> values;
  };
  std::vector<std::string> order;
  std::map<std::string, Cell> cells;
  for (const RunRow& r : rows) {
    const std::string key = r.at("plant_spacing") + "|" + r.at("row_spacing") + "|" + r.at("steps");
    if (!cells.count(key)) order.push_back(key), cells[key].first = r;
    Cell& c = cells[key];
    ++c.runs;
    if (r.at("status") != "ok") {
      ++c.failed;
      continue;
    }
    for (const std::string& m : metrics)
      if (const auto v = finite_number(r.at(m))) c.values[m].push_back(*v);
  }
  std::string out = "plant_spacing,row_spacing,density,steps,runs,failed";
  for (const std::string& m : metrics) out += "," + m + "_mean," + m + "_sd";
  out += "\n";
  for (const std::string& key : order) {
    const Cell& c = cells[key];
    out += fmt::format("{},{},{},{},{},{}", c.first.at("plant_spacing"), c.first.at("row_spacing"),
                       c.first.at("density"), c.first.at("steps"), c.runs, c.failed);
    for (const std::string& m : metrics) {
      const auto it = c.values.find(m);
      if (it == c.values.end() || it->second.empty()) {
        out += ",,";
        continue;
      }
      const std::vector<double>& v = it->second;
      double mean = 0, ss = 0;
      for (double x : v) mean += x;
      mean /= static_cast<double>(v.size());
      for (double x : v) ss += (x - mean) * (x - mean);
      // The sample standard deviation (n - 1): none for one value (it was written 0).
      out += fmt::format(",{:.6g},", mean);
      if (v.size() > 1) out += fmt::format("{:.6g}", std::sqrt(ss / static_cast<double>(v.size() - 1)));
    }
    out += "\n";
  }
  return out;
}

}  // namespace canopy::cli
