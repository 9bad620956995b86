// Derivation speed: modules per second (all modules written over all steps / wall time) for the
// grammars given, median of repeats, one thread. Prints a table and writes CSV.
#include "geometry/clock.hpp"
#include "lsystem/derive.hpp"
#include "lsystem/grammar.hpp"
#include "tools/bench_timing.hpp"
#include "tools/bench_usage.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

using namespace canopy;

namespace {

struct Case {
  std::string file;
  int steps;
};

}  // namespace

int main(int argc, char** argv) {
  std::vector<Case> cases;
  std::string csv = "bench/results/derive.csv";
  int repeats = 5;
  const std::string usage = "usage: bench_derive GRAMMAR[:STEPS]... [--repeats N] [--csv FILE]\n";
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) csv = argv[++i];
    else if (!std::strcmp(argv[i], "--repeats") && i + 1 < argc) repeats = std::max(1, std::atoi(argv[++i]));
    else if (argv[i][0] == '-') return help_or_refuse("bench_derive", argv[i], usage);  // not a grammar file
    else {
      std::string a = argv[i];
      const auto colon = a.rfind(':');
      if (colon != std::string::npos && colon + 1 < a.size() &&
          std::isdigit(static_cast<unsigned char>(a[colon + 1])))
        cases.push_back({a.substr(0, colon), std::atoi(a.c_str() + colon + 1)});
      else cases.push_back({a, -1});
    }
  }
  if (cases.empty()) {
    std::fputs(usage.c_str(), stderr);
    return 2;
  }
  // Rows are kept until every case has run, so a grammar that fails to load leaves an earlier
  // CSV as it was.
  std::string rows = "grammar,engine,steps,final_modules,modules_written,median_s,modules_per_s\n";
  fmt::print("{:<40} {:>6} {:>14} {:>16} {:>10} {:>14}\n", "grammar", "steps", "final modules",
             "modules written", "median s", "Mmodules/s");
  for (const Case& c : cases) {
    Grammar g;
    try {
      g = load_grammar(c.file);
    } catch (const std::exception& e) {
      fmt::print(stderr, "bench_derive: {}\n", e.what());
      return 1;
    }
    const int steps = c.steps >= 0 ? c.steps : g.steps;
    // Count what the derivation writes: the sum of the string lengths after each step.
    std::size_t written = 0, final_size = 0;
    for (int k = 1; k <= steps; ++k) {
      final_size = derive(g, DeriveRequest{k, g.seed, kDefaultMaxModules}).size();
      written += final_size;
    }
    // Each timing repeats the derivation often enough to last about 0.1 s.
    int loops = 1;
    for (;;) {
      const auto t0 = std::chrono::steady_clock::now();
      for (int l = 0; l < loops; ++l) derive(g, DeriveRequest{steps, g.seed, kDefaultMaxModules});
      if (seconds_since(t0) > 0.05 || loops > (1 << 24)) break;
      loops *= 4;
    }
    std::vector<double> times;
    for (int r = 0; r < repeats; ++r) {
      const auto t0 = std::chrono::steady_clock::now();
      for (int l = 0; l < loops; ++l) {
        const ModuleString s = derive(g, DeriveRequest{steps, g.seed, kDefaultMaxModules});
        if (s.size() != final_size) throw std::runtime_error("nondeterministic derivation length");
      }
      times.push_back(seconds_since(t0) / loops);
    }
    const double med = median(std::move(times));
    const double rate = static_cast<double>(written) / med;
    fmt::print("{:<40} {:>6} {:>14} {:>16} {:>10.4f} {:>14.1f}\n", c.file, steps, final_size, written, med,
               rate / 1e6);
    rows += fmt::format("{},canopy,{},{},{},{:.6f},{:.0f}\n", c.file, steps, final_size, written, med, rate);
  }
  std::FILE* out = std::fopen(csv.c_str(), "w");
  if (!out || std::fputs(rows.c_str(), out) < 0 || std::fclose(out) != 0) {
    fmt::print(stderr, "bench_derive: cannot write {}\n", csv);
    return 1;
  }
  fmt::print("wrote {}\n", csv);
  return 0;
}
