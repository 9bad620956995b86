#include "tools/report.hpp"

#include <fmt/format.h>

#include <numeric>

namespace canopy::cli {

std::vector<std::size_t> triangles_per_plant(const Stand& s, PrototypeLibrary& lib) {
  std::vector<std::size_t> t(s.plant_count(), 0);
  for (const OrganRecord& r : s.organs) t[static_cast<std::size_t>(r.plant)] += lib.get(r.prototype, r.lod).triangle_count();
  return t;
}

void write_report(const Stand& s, PrototypeLibrary& lib, const StandReport& r, AtomicFile& out) {
  out.write(report_json(s, lib, r).dump(2) + "\n");
}

nlohmann::ordered_json report_json(const Stand& s, PrototypeLibrary& lib, const StandReport& r) {
  nlohmann::ordered_json j;
  j["canopy_version"] = CANOPY_VERSION;
  j["config"] = r.config;
  j["grammar"] = r.grammar;
  j["seed"] = r.seed;
  j["stand_origin"] = {s.stand_origin.x, s.stand_origin.y, s.stand_origin.z};
  const auto tris = triangles_per_plant(s, lib);
  std::vector<std::size_t> organs(s.plant_count());
  for (std::size_t p = 0; p < s.plant_count(); ++p) organs[p] = s.plants[p].organ_count;
  j["counts"] = {{"plants", s.plant_count()},
                 {"organs", s.organ_count()},
                 {"triangles", std::accumulate(tris.begin(), tris.end(), std::size_t{0})},
                 {"organs_per_plant", organs},
                 {"triangles_per_plant", tris}};
  nlohmann::ordered_json t;
  for (const auto& [k, v] : r.timings) t[k] = v;
  j["timings_s"] = t;
  j["backend"] = r.backend;
  j["device"] = r.device;
  j["contacts_before"] = r.contacts_before;
  j["contacts_after"] = r.contacts_after;
  j["resolution"] = r.resolution;
  return j;
}

void print_summary(const Stand& s, PrototypeLibrary& lib, const StandReport& r, const std::string& dir) {
  const auto tris = triangles_per_plant(s, lib);
  const std::size_t total = std::accumulate(tris.begin(), tris.end(), std::size_t{0});
  const double n = std::max<double>(1, static_cast<double>(s.plant_count()));
  fmt::print("stand: {} plants, {} organs ({:.0f} per plant), {} triangles ({:.0f} per plant)\n", s.plant_count(),
             s.organ_count(), static_cast<double>(s.organ_count()) / n, total, static_cast<double>(total) / n);
  for (const auto& [k, v] : r.timings) fmt::print("  {:<10} {:.3f} s\n", k, v);
  fmt::print("wrote {}\n", dir);
}

}  // namespace canopy::cli
