#include "tools/sweep_table.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

namespace canopy::cli {
namespace {

const std::vector<std::string> kKey{"plant_spacing", "row_spacing", "steps", "seed"};
const std::vector<std::string> kText{"status", "message"};

/// Splits one CSV line (quoted fields with doubled quotes); false when a quote is left open.
bool split_csv(const std::string& line, std::vector<std::string>& out) {
  out.clear();
  std::string f;
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') f += '"', ++i;
      else if (c == '"') quoted = false;
      else f += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      out.push_back(f), f.clear();
    } else {
      f += c;
    }
  }
  out.push_back(f);
  return !quoted;
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
  static const std::vector<std::string> c{
      "run", "plant_spacing", "row_spacing", "density", "steps", "seed", "status", "plants", "organs", "lai", "lai_plants",
      "plant_between_per_plant", "plant_within_per_plant", "leaf_between_per_plant", "leaf_within_per_plant",
      "organ_between_per_plant", "organ_within_per_plant", "exact_between_per_plant", "exact_within_per_plant",
      "organs_turned", "organs_turned_per_plant", "mean_turn_deg", "max_turn_deg", "rounds", "residual_contacts",
      "ground_cover_before", "direct_before", "diffuse_before", "star_before", "mean_inclination_before", "light_se_before",
      "ground_cover_after", "direct_after", "diffuse_after", "star_after", "mean_inclination_after", "light_se_after",
      "generate_s", "detect_s", "resolve_s", "light_s", "backend", "message"};
  return c;
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' ? ' ' : c);
  return q + "\"";
}

std::string run_key(const RunRow& r) {
  std::string k;
  for (const std::string& c : kKey) k += (k.empty() ? "" : "|") + (r.count(c) ? r.at(c) : "");
  return k;
}

std::vector<RunRow> read_runs(const std::string& path) {
  std::ifstream in(path);
  std::vector<RunRow> rows;
  if (!in) return rows;
  std::string line;
  if (!std::getline(in, line)) return rows;
  if (line + "\n" != header())
    throw std::invalid_argument(fmt::format("{}: not a runs.csv of this canopy version (header differs); use another -o", path));
  std::vector<std::string> f;
  while (std::getline(in, line)) {
    if (!split_csv(line, f) || f.size() != run_columns().size()) continue;  // a torn last line
    RunRow r;
    for (std::size_t i = 0; i < f.size(); ++i) r[run_columns()[i]] = f[i];
    rows.push_back(std::move(r));
  }
  return rows;
}

void write_runs(const std::string& path, const std::vector<RunRow>& rows) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << header();
    for (const RunRow& r : rows) out << line_of(r);
    if (!out) throw std::runtime_error(fmt::format("cannot write {}", tmp));
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) throw std::runtime_error(fmt::format("cannot rename {} to {}", tmp, path));
}

void append_run(const std::string& path, const RunRow& row) {
  std::FILE* f = std::fopen(path.c_str(), "a");
  if (!f) throw std::runtime_error(fmt::format("cannot append to {}", path));
  const std::string l = line_of(row);
  const bool ok = std::fwrite(l.data(), 1, l.size(), f) == l.size() && std::fflush(f) == 0 && fsync(fileno(f)) == 0;
  std::fclose(f);
  if (!ok) throw std::runtime_error(fmt::format("cannot append to {}", path));
}

std::string summary_csv(const std::vector<RunRow>& rows) {
  std::vector<std::string> metrics;
  for (const std::string& c : run_columns())
    if (c != "run" && c != "seed" && c != "backend" && c != "plant_spacing" && c != "row_spacing" && c != "steps" &&
        c != "density" && c != "status" && c != "message")
      metrics.push_back(c);
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
      if (!r.at(m).empty()) c.values[m].push_back(std::stod(r.at(m)));
  }
  std::string out = "plant_spacing,row_spacing,density,steps,runs,failed";
  for (const std::string& m : metrics) out += "," + m + "_mean," + m + "_sd";
  out += "\n";
  for (const std::string& key : order) {
    const Cell& c = cells[key];
    out += fmt::format("{},{},{},{},{},{}", c.first.at("plant_spacing"), c.first.at("row_spacing"), c.first.at("density"),
                       c.first.at("steps"), c.runs, c.failed);
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
      const double sd = v.size() > 1 ? std::sqrt(ss / static_cast<double>(v.size() - 1)) : 0.0;
      out += fmt::format(",{:.6g},{:.6g}", mean, sd);
    }
    out += "\n";
  }
  return out;
}

}  // namespace canopy::cli
