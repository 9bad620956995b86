#pragma once
/// What every run of a sweep shares besides its cell and seed (the grammar's YAML document, --set's values,
/// the stand's rows, jitter and detail, detection's and resolution's settings), kept in the sweep's folder as
/// sweep.json: a resumed sweep must ask for the same, or its rows would mix stands of two kinds in one table.
/// Settings that change no answer (backend, threads, lanes, search) are left out.
#include "tools/sweep_run.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace canopy::cli {

/// The shared settings of a sweep, as sweep.json holds them.
nlohmann::ordered_json sweep_settings(const SweepOptions& o);

/// On starting a sweep in `dir` (whose runs.csv holds `finished_runs` rows): with rows there and
/// a sweep.json, throws std::invalid_argument naming each setting that differs; otherwise (a new
/// sweep, or one from before sweep.json) writes `settings` into sweep.json.
void check_sweep_settings(const std::string& dir, const nlohmann::ordered_json& settings,
                          std::size_t finished_runs);

}  // namespace canopy::cli
