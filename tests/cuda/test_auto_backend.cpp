// `--backend auto` on a GPU is the CUDA backend whole: `canopy stand`'s files, byte for byte,
// those of `--backend cuda`, and resolution planned with the device's attempts in both, as
// report.json says. (Skipped without a GPU: see test_device.cpp.)
#include "../collision/helpers.hpp"
#include "tools/stand_run.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

using namespace canopy;
using namespace canopy::test;
namespace fs = std::filesystem;

namespace {

std::string bytes_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// report.json without what differs between the two runs by design: the timings and memory
/// peaks, the backend asked for (config.backend) and how it was chosen (backend_choice).
nlohmann::ordered_json comparable(nlohmann::ordered_json r) {
  r.erase("timings_s");
  r.erase("peak_memory_gb");
  r.erase("backend_choice");
  r["config"].erase("backend");
  r["config"].erase("out");  // the two runs write two folders
  for (auto& round : r["resolution"]["rounds"]) round.erase("plan_s"), round.erase("detect_s");
  return r;
}

}  // namespace

TEST_CASE("--backend auto on a GPU: the files of --backend cuda, planned with the device's attempts") {
  const fs::path root = fs::temp_directory_path() / fmt::format("canopy_auto_{}", getpid());
  struct Case {
    const char* name;
    int rows, per_row;
    double row_spacing, plant_spacing;  // 0: the grammar entry's
  };
  // 300 plants of the default stand, and 12 dense plants with fruit among the leaves (6.7 plants
  // per m2, where the default resolution clears every contact: tests/tools/test_cgal.sh).
  for (const Case& k : {Case{"default stand", 3, 100, 0, 0}, Case{"dense", 3, 4, 0.5, 0.3}}) {
    INFO(k.name);
    nlohmann::ordered_json reports[2];
    const char* backends[2] = {"cuda", "auto"};
    for (int b = 0; b < 2; ++b) {
      cli::StandOptions o;
      o.grammar = source("grammars/tomato.yaml");
      o.out = (root / backends[b]).string();
      o.formats = "glb,obj,ply";
      o.rows.rows = k.rows, o.rows.per_row = k.per_row;
      if (k.row_spacing > 0) o.rows.row_spacing = k.row_spacing, o.rows.plant_spacing = k.plant_spacing;
      o.detect.backend = backends[b];
      o.resolve.progress = false;
      reports[b] = cli::run_stand(o, false).report;
    }
    for (const auto& f : fs::directory_iterator(root / "cuda")) {
      const std::string name = f.path().filename().string();
      INFO(name);
      if (name == "report.json") continue;
      CHECK(bytes_of(f.path()) == bytes_of(root / "auto" / name));
    }
    CHECK(comparable(reports[0]) == comparable(reports[1]));
    for (const auto& r : reports) {
      CHECK(r["backend"] == "cuda");
      CHECK(r["resolution"]["contacts_before"].get<std::size_t>() > 0);
      CHECK(r["resolution"]["contacts_after"] == 0);
      CHECK(r["resolution"]["search"] == "device");
      CHECK(r["resolution"]["planning"] ==
            fmt::format("device attempts, {} lanes", ResolveRequest{}.bulk_lanes));
    }
    MESSAGE(k.name << ": " << reports[1]["resolution"]["contacts_before"] << " contacts, planned with "
                   << reports[1]["resolution"]["planning"] << " on " << reports[1]["device"]);
  }
  fs::remove_all(root);
}
