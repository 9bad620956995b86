#include "resolution/phase_times.hpp"

#include <sys/resource.h>

namespace canopy {

PhaseTimes::Usage PhaseTimes::usage() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return {static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
              1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec),
          u.ru_minflt};
}

void PhaseTimes::lap(Phase p) {
  if (!on) return;
  const double t = now_seconds();
  const Usage u = usage();
  seconds[p] += t - mark, mark = t;
  cpu[p] += u.cpu - usage_mark.cpu, faults[p] += u.faults - usage_mark.faults, usage_mark = u;
}

std::vector<PhaseStat> PhaseTimes::phases() const {
  static constexpr const char* names[count] = {"setup", "witnesses", "candidates",  "bookkeeping",
                                               "scan",  "pick",      "last resort", "apply turns",
                                               "refit", "redetect",  "merge",       "release"};
  std::vector<PhaseStat> out;
  for (int p = 0; p < count; ++p) out.push_back({names[p], seconds[p], cpu[p], faults[p]});
  return out;
}

}  // namespace canopy
