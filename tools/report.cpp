#include "tools/report.hpp"

#include <fmt/format.h>

#include <numeric>

namespace canopy::cli {

std::vector<std::size_t> triangles_per_plant(const Stand& s, PrototypeLibrary& lib) {
  std::vector<std::size_t> t(s.plant_count(), 0);
  for (const OrganRecord& r : s.organs) t[static_cast<std::size_t>(r.plant)] += lib.get(r).triangle_count();
  return t;
}

StandCounts stand_counts(const Stand& s, PrototypeLibrary& lib) {
  StandCounts c{s.stand_origin, std::vector<std::size_t>(s.plant_count()), triangles_per_plant(s, lib)};
  for (std::size_t p = 0; p < s.plant_count(); ++p) c.organs[p] = s.plants[p].organ_count;
  return c;
}

nlohmann::ordered_json report_json(const StandCounts& c, const StandReport& r) {
  nlohmann::ordered_json j;
  j["canopy_version"] = CANOPY_VERSION;
  j["config"] = r.config;
  j["grammar"] = r.grammar;
  j["seed"] = r.seed;
  j["stand_origin"] = {c.stand_origin.x, c.stand_origin.y, c.stand_origin.z};
  j["counts"] = {{"plants", c.organs.size()},
                 {"organs", std::accumulate(c.organs.begin(), c.organs.end(), std::size_t{0})},
                 {"triangles", std::accumulate(c.triangles.begin(), c.triangles.end(), std::size_t{0})},
                 {"organs_per_plant", c.organs},
                 {"triangles_per_plant", c.triangles}};
  nlohmann::ordered_json t;
  for (const auto& [k, v] : r.timings) t[k] = v;
  j["timings_s"] = t;
  nlohmann::ordered_json m = nlohmann::ordered_json::object();
  for (const auto& [k, v] : r.peak_memory)
    if (v > 0) m[k] = v;
  j["peak_memory_gb"] = m;
  j["backend"] = r.backend;
  j["device"] = r.device;
  j["backend_choice"] = r.backend_choice;
  j["contacts_before"] = r.contacts_before;
  j["contacts_after"] = r.contacts_after;
  j["resolution"] = r.resolution;
  j["leaf_angles"] = r.leaf_angles;
  return j;
}

nlohmann::ordered_json leaf_angles_json(const LeafAngles& a) {
  nlohmann::ordered_json j;
  j["leaf_area"] = a.leaf_area;
  j["bin_deg"] = kLeafAngleBinDeg;
  nlohmann::ordered_json bins = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < a.area.size(); ++i)
    bins.push_back({{"from_deg", kLeafAngleBinDeg * static_cast<double>(i)},
                    {"to_deg", kLeafAngleBinDeg * static_cast<double>(i + 1)},
                    {"area", a.area[i]},
                    {"fraction", a.fraction[i]}});
  j["bins"] = bins;
  j["mean_inclination_deg"] = a.mean_inclination_deg;
  nlohmann::ordered_json g = nlohmann::ordered_json::array();
  for (std::size_t k = 0; k < kGZenithsDeg.size(); ++k)
    g.push_back({{"zenith_deg", kGZenithsDeg[k]}, {"g", a.g[k]}});
  j["g"] = g;
  return j;
}

void print_summary(const StandCounts& c, const StandReport& r, const std::string& dir) {
  const std::size_t organs = std::accumulate(c.organs.begin(), c.organs.end(), std::size_t{0});
  const std::size_t total = std::accumulate(c.triangles.begin(), c.triangles.end(), std::size_t{0});
  const double n = std::max<double>(1, static_cast<double>(c.organs.size()));
  fmt::print("stand: {} plants, {} organs ({:.0f} per plant), {} triangles ({:.0f} per plant)\n",
             c.organs.size(), organs, static_cast<double>(organs) / n, total, static_cast<double>(total) / n);
  for (const auto& [k, v] : r.timings) fmt::print("  {:<10} {:.3f} s\n", k, v);
  std::string peaks;
  for (const auto& [k, v] : r.peak_memory)
    if (v > 0) peaks += fmt::format("{}{} {:.2f}", peaks.empty() ? "" : ", ", k, v);
  if (!peaks.empty()) fmt::print("  peak memory (GB): {}\n", peaks);
  fmt::print("wrote {}\n", dir);
}

}  // namespace canopy::cli
