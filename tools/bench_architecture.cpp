// What a grown tomato looks like in the numbers agronomists compare (docs/tomato.md): per
// grammar, the organs and triangles per plant, leaves per plant, plant height, one-sided leaf
// area per plant, the leaf area index of the stand at its density (inner plants), and the leaf
// inclination distribution (the angle of the blade's normal from the vertical, area-weighted).
// Prints a table and writes CSV.
// Usage: bench_architecture [--rows 3] [--per-row 10] [--plant-spacing 0.4] [--row-spacing 1.0]
//                           [--seed 1] [--lod 2] [--csv FILE] GRAMMAR...
#include "geometry/layout.hpp"
#include "geometry/stand_metrics.hpp"
#include "lsystem/grow.hpp"
#include "tools/bench_usage.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <numeric>
#include <string>
#include <vector>

using namespace canopy;

namespace {

double mean(const std::vector<double>& v) {
  return v.empty() ? 0 : std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

}  // namespace

int main(int argc, char** argv) {
  const std::string usage =
      "usage: bench_architecture [--rows 3] [--per-row 10] [--plant-spacing 0.4] [--row-spacing 1.0] [--seed "
      "1] [--lod 2] "
      "[--csv FILE] GRAMMAR...\n";
  RowLayout layout;
  layout.rows = 3, layout.per_row = 10, layout.row_spacing = 1.0, layout.plant_spacing = 0.4;
  layout.random_rotation = true, layout.jitter = 0.02, layout.seed = 1;
  int lod = kDefaultLod;
  std::string csv = "bench/results/architecture.csv";
  std::vector<std::string> grammars;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool value = i + 1 < argc;
    try {
      if (a == "--rows" && value) layout.rows = std::stoi(argv[++i]);
      else if (a == "--per-row" && value) layout.per_row = std::stoi(argv[++i]);
      else if (a == "--plant-spacing" && value) layout.plant_spacing = std::stod(argv[++i]);
      else if (a == "--row-spacing" && value) layout.row_spacing = std::stod(argv[++i]);
      else if (a == "--seed" && value) layout.seed = std::stoull(argv[++i]);
      else if (a == "--lod" && value) lod = std::stoi(argv[++i]);
      else if (a == "--csv" && value) csv = argv[++i];
      else if (!a.empty() && a[0] != '-') grammars.push_back(a);
      else return help_or_refuse("bench_architecture", argv[i], usage);
    } catch (const std::exception&) {
      return help_or_refuse("bench_architecture", argv[i], usage);
    }
  }
  if (grammars.empty() || layout.rows < 1 || layout.per_row < 1 || !(layout.plant_spacing > 0) ||
      !(layout.row_spacing > 0) || lod < 1 || lod > kMaxLod) {
    std::fprintf(stderr,
                 "bench_architecture: name a grammar; rows, plants per row, spacings and the level of detail "
                 "must be positive\n%s",
                 usage.c_str());
    return 2;
  }
  const int bins = 9;
  std::string text =
      "grammar,plants,density_per_m2,organs_per_plant,triangles_per_plant,leaves_per_plant,height_m,leaf_"
      "area_m2,lai,"
      "mean_inclination_deg";
  for (int b = 0; b < bins; ++b) text += fmt::format(",incl_{}_{}", b * 10, b * 10 + 10);
  text += '\n';
  fmt::print(
      "{:<28} {:>7} {:>9} {:>7} {:>7} {:>9} {:>6} {:>10}  inclination, % of leaf area by 10-degree class\n",
      "grammar", "organs", "triangles", "leaves", "height", "leaf m2", "LAI", "mean incl");
  for (const std::string& g : grammars) {
    GrowRequest req;
    req.grammar = g;
    req.plants = row_layout(layout);
    req.lod = lod;
    Stand s;
    try {
      s = grow_stand(req);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "bench_architecture: error: %s\n", e.what());
      return 1;  // nothing written
    }
    PrototypeLibrary lib;
    std::size_t triangles = 0, leaves = 0;
    for (std::size_t i = 0; i < s.organ_count(); ++i) triangles += lib.get(s.organs[i]).triangle_count();
    for (const PlantRecord& p : s.plants) leaves += p.leaf_count;
    const double n = static_cast<double>(s.plant_count());
    const LeafAreaIndex lai =
        leaf_area_index(s, lib, layout.rows, layout.per_row, layout.plant_spacing, layout.row_spacing);
    const LeafInclination inc = leaf_inclination(s, lib, bins);
    const double height = mean(plant_heights(s, lib)), area = mean(leaflet_area_per_plant(s, lib));
    const double density = 1 / (layout.plant_spacing * layout.row_spacing);
    std::string classes;
    text += fmt::format("{},{},{:.4f},{:.1f},{:.1f},{:.2f},{:.4f},{:.5f},{:.4f},{:.3f}", g, s.plant_count(),
                        density, static_cast<double>(s.organ_count()) / n, static_cast<double>(triangles) / n,
                        static_cast<double>(leaves) / n, height, area, lai.lai, inc.mean_deg);
    for (double f : inc.fraction)
      classes += fmt::format(" {:>4.1f}", 100 * f), text += fmt::format(",{:.5f}", f);
    text += '\n';
    fmt::print("{:<28} {:>7.0f} {:>9.0f} {:>7.1f} {:>7.2f} {:>9.3f} {:>6.2f} {:>10.1f} {}\n", g,
               static_cast<double>(s.organ_count()) / n, static_cast<double>(triangles) / n,
               static_cast<double>(leaves) / n, height, area, lai.lai, inc.mean_deg, classes);
  }
  std::FILE* out = std::fopen(csv.c_str(), "w");
  if (!out || std::fputs(text.c_str(), out) < 0 || std::fclose(out) != 0) {
    std::fprintf(stderr, "bench_architecture: error: cannot write %s\n", csv.c_str());
    return 1;
  }
  fmt::print("wrote {}\n", csv);
  return 0;
}
