// libFuzzer target: any bytes as a positions file (canopy stand --positions). A located
// std::invalid_argument is the expected way out; what is read must be what the reader promises
// (finite numbers, steps in range, grammar cells inside the file's folder unless allowed).
#include "fuzz_files.hpp"
#include "geometry/layout.hpp"

#include <cmath>
#include <cstdlib>
#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = canopy::fuzz::put("positions.csv", {reinterpret_cast<const char*>(data), size});
  for (const bool any_grammar_path : {false, true}) {
    try {
      for (const canopy::PlantPlacement& p : canopy::read_positions(path, any_grammar_path)) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.rotation_deg)) std::abort();
        if (p.steps && (*p.steps < 0 || *p.steps > canopy::kMaxSteps)) std::abort();
        const std::filesystem::path g = std::filesystem::path(p.grammar).lexically_normal();
        if (!any_grammar_path && (g.is_absolute() || (!g.empty() && *g.begin() == ".."))) std::abort();
      }
    } catch (const std::invalid_argument&) {
    }
  }
  return 0;
}
