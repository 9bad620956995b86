#include "collision/phase_times.hpp"

#include <fmt/format.h>
#include <sys/resource.h>

#include <string>

namespace canopy {

PhaseTimes::Usage PhaseTimes::usage() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return {static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec),
          u.ru_minflt};
}

void PhaseTimes::lap(Phase p) {
  if (!on) return;
  const double t = now_seconds();
  const Usage u = usage();
  seconds[p] += t - mark, mark = t;
  cpu[p] += u.cpu - usage_mark.cpu, faults[p] += u.faults - usage_mark.faults, usage_mark = u;
}

void PhaseTimes::print(int threads) const {
  if (!on) return;
  static constexpr const char* names[count] = {"setup", "witnesses", "candidates", "bookkeeping", "scan", "pick",
                                               "last resort", "apply turns", "refit", "redetect", "merge", "release"};
  std::string line = "resolution phases (s):";
  for (int p = 0; p < count; ++p) line += fmt::format(" {} {:.3f},", names[p], seconds[p]);
  fmt::print(stderr, "{} scan busy {:.2f} thread-s on {} threads; CPU s (all threads) setup to candidates {:.2f}, scan {:.2f}, the rest {:.2f}\n",
             line, scan_busy, threads, cpu[setup] + cpu[witnesses] + cpu[candidates], cpu[scan],
             cpu[bookkeeping] + cpu[pick] + cpu[last_resort] + cpu[apply] + cpu[refit] + cpu[redetect] + cpu[merge] + cpu[release]);
  std::string pages = "resolution minor page faults (thousands):";
  for (int p = 0; p < count; ++p) pages += fmt::format(" {} {:.1f},", names[p], 1e-3 * static_cast<double>(faults[p]));
  fmt::print(stderr, "{}\n", pages);
}

}  // namespace canopy
