// libFuzzer target: any bytes as a sweep folder's runs.csv and sweep.json (cut at the first NUL
// byte), read as canopy sweep reads them on resuming. std::invalid_argument naming the file is the
// expected way out; rows that are read make a summary without any exception.
#include "fuzz_files.hpp"
#include "tools/sweep_table.hpp"

#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto [runs, settings] = canopy::fuzz::two_parts(data, size);
  const std::string runs_path = canopy::fuzz::put("runs.csv", runs);
  const std::string settings_path = canopy::fuzz::put("sweep.json", settings);
  std::vector<canopy::cli::RunRow> rows;
  try {
    rows = canopy::cli::read_runs(runs_path);
  } catch (const std::invalid_argument&) {
  }
  // Rows that were read make a summary without any exception (std::stod threw on a word).
  for (const auto& r : rows) (void)canopy::cli::run_key(r);
  (void)canopy::cli::summary_csv(rows);
  try {
    const nlohmann::ordered_json before = canopy::cli::read_sweep_settings(settings_path);
    // As check_sweep_settings uses it: looked up, compared and printed.
    for (const auto& [key, value] : before.items()) {
      if (!before.contains(key) || before.at(key) != value) std::abort();
      (void)value.dump();
    }
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
