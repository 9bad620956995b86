#pragma once
/// report.json (docs/design.md "Report") and the terminal summary of a run.
#include "geometry/atomic_file.hpp"
#include "geometry/leaf_angles.hpp"
#include "geometry/prototype.hpp"
#include "geometry/stand.hpp"

#include <nlohmann/json.hpp>

#include <map>
#include <string>

namespace canopy::cli {

struct StandReport {
  nlohmann::ordered_json config;
  std::string grammar;
  nlohmann::ordered_json seed;
  std::map<std::string, double> timings;  // seconds per stage
  /// Per stage: the process's resident peak during it, GB (tools/stage_memory.hpp; empty or 0
  /// where the system does not say).
  std::map<std::string, double> peak_memory;
  /// The backend and device that ran, taken after the last detection (a backend that fell back
  /// half-way names the one that finished, and its device says what failed), and how the
  /// backend was chosen (make_backend's note: asked for, or what auto found).
  std::string backend = "none";
  nlohmann::ordered_json device = nullptr;
  std::string backend_choice;
  nlohmann::ordered_json contacts_before = nullptr, contacts_after = nullptr, resolution = nullptr;
  nlohmann::ordered_json leaf_angles = nullptr;  // of the stand as exported (leaf_angles_json)
};

/// The leaf angle distribution as report.json and light.json give it: leaflet area, 5-degree
/// inclination bins (area and fraction), mean inclination, G at a few zenith angles.
nlohmann::ordered_json leaf_angles_json(const LeafAngles& a);

/// Triangles of each plant at its organs' levels of detail.
std::vector<std::size_t> triangles_per_plant(const Stand& stand, PrototypeLibrary& lib);

/// What report.json's "counts" and "stand_origin" say of a stand (held whole or in tiles).
struct StandCounts {
  Vec3d stand_origin;
  std::vector<std::size_t> organs, triangles;  // per plant
};
StandCounts stand_counts(const Stand& stand, PrototypeLibrary& lib);

/// report.json's content.
nlohmann::ordered_json report_json(const StandCounts& counts, const StandReport& r);
void print_summary(const StandCounts& counts, const StandReport& r, const std::string& dir);

}  // namespace canopy::cli
