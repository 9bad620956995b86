#include "tools/folder_counts.hpp"

#include "geometry/input_file.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <filesystem>

namespace canopy::cli {

std::vector<std::string> folder_count_notes(const std::string& dir, const Stand& s,
                                            const FolderIdentity& before) {
  const std::string path = (std::filesystem::path(dir) / "report.json").string();
  // Read as every user file is: a regular file of bounded size (a FIFO there would wait for ever).
  std::string text;
  try {
    text = read_input_file(path, "report", kMaxReportBytes);
  } catch (const std::exception&) {
    return {};  // no report, or not one canopy wrote: nothing to compare with
  }
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("counts") || !j["counts"].is_object()) return {};
  const nlohmann::json& c = j["counts"];
  const auto count = [&](const char* key) -> long long {
    return c.contains(key) && c[key].is_number_unsigned() ? c[key].get<long long>() : -1;
  };
  const long long plants = count("plants"), organs = count("organs");
  if ((plants < 0 || plants == static_cast<long long>(s.plant_count())) &&
      (organs < 0 || organs == static_cast<long long>(s.organ_count())))
    return {};
  // Another run replaced the folder while it was read: its report counts another stand (1 to 5
  // reads in 150 said the tables were cut short while runs replaced the folder).
  if (!(folder_identity(dir, "organs.csv") == before)) return {};
  return {fmt::format("{}: the tables hold {} plants and {} organs, its report.json counted {} and {}: they "
                      "were changed or cut short since canopy stand wrote them",
                      dir, s.plant_count(), s.organ_count(), plants, organs)};
}

}  // namespace canopy::cli
