#include "tools/folder_counts.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

namespace canopy::cli {

std::vector<std::string> folder_count_notes(const std::string& dir, const Stand& s) {
  const std::string path = (std::filesystem::path(dir) / "report.json").string();
  std::ifstream in(path);
  if (!in) return {};
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("counts") || !j["counts"].is_object()) return {};
  const nlohmann::json& c = j["counts"];
  const auto count = [&](const char* key) -> long long {
    return c.contains(key) && c[key].is_number_unsigned() ? c[key].get<long long>() : -1;
  };
  const long long plants = count("plants"), organs = count("organs");
  if ((plants < 0 || plants == static_cast<long long>(s.plant_count())) &&
      (organs < 0 || organs == static_cast<long long>(s.organ_count())))
    return {};
  return {fmt::format("{}: the tables hold {} plants and {} organs, its report.json counted {} and {}: they "
                      "were changed or cut short since canopy stand wrote them",
                      dir, s.plant_count(), s.organ_count(), plants, organs)};
}

}  // namespace canopy::cli
