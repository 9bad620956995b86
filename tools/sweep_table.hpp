#pragma once
/// The sweep's files: runs.csv (one row per run, appended and flushed as each run ends, so an
/// interrupted sweep loses at most the run in progress) and summary.csv (mean and standard
/// deviation per cell over its finished runs).
#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <vector>

namespace canopy::cli {

/// runs.csv columns, in order.
const std::vector<std::string>& run_columns();

/// One row: column name -> text (numbers already formatted).
using RunRow = std::map<std::string, std::string>;

/// The key of a run: its cell and seed, as written in runs.csv.
std::string run_key(const RunRow& r);

/// Rows of an existing runs.csv (a missing file gives none; a torn last line, from a run killed
/// while writing, is dropped). Throws std::invalid_argument when the header is not ours, a line
/// other than the last is not a whole row, a run has two rows, a measured column holds something
/// other than a number, or the file is not a regular file of at most kMaxRunsCsvBytes.
std::vector<RunRow> read_runs(const std::string& path);
/// sweep.json as an earlier run of the sweep wrote it: a JSON object of at most
/// kMaxSweepJsonBytes nested at most 16 levels; throws std::invalid_argument naming the file
/// otherwise.
nlohmann::ordered_json read_sweep_settings(const std::string& path);
/// Rewrites runs.csv with `rows` (used once at start, to drop a torn line and replaced failures).
void write_runs(const std::string& path, const std::vector<RunRow>& rows);
/// Appends one row and flushes it to the disk.
void append_run(const std::string& path, const RunRow& row);

/// summary.csv from the rows: per cell (plant spacing, row spacing, steps) the number of runs,
/// failures, and mean / standard deviation of every numeric column of finished runs.
std::string summary_csv(const std::vector<RunRow>& rows);

}  // namespace canopy::cli
