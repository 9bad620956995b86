#pragma once
/// The one rerun of a program at its start, with what its run wants of the environment that
/// glibc and libgomp read only when a process starts (before main):
///   - large heap pages for runs on the GPU (glibc.malloc.hugetlb=1, tools/heap_pages.hpp);
///   - OpenMP's waiting threads asleep instead of spinning (OMP_WAIT_POLICY=passive) for the
///     commands that run parallel work, unless OMP_WAIT_POLICY or GOMP_SPINCOUNT is set.
///
/// Why passive waits: libgomp's default spins a waiting thread for about 300,000 rounds before it
/// sleeps. canopy runs many short parallel regions (resolution's levels, the export's waves) beside
/// threads of its own (the export's writer, resolution's lanes, the GPU's), and a thread spinning
/// at a barrier takes the core another thread of the run, or another program, needs. On the
/// 2-core machine, `canopy stand grammars/tomato.yaml` (100 plants) beside one busy process took
/// 0.52-0.97 s passive against 0.73-2.58 s spinning (4 runs each, alternated); on a 16-core H100
/// host bench_stand used 30-40 % less CPU time passive, for 0.90-0.93 s against 0.96-1.14 s at
/// 1,000 plants on the GPU and the same wall time within the noise at 10,000 (3 runs each).
///
/// A library cannot choose this for its host (the Python module keeps OpenMP's default), and a
/// function of the executable's .preinit_array is too early (glibc sets its environment back to
/// the one the process started with after it), hence the rerun. It costs one exec (a few
/// milliseconds) where nothing else asked for one; a GPU run makes it anyway for its heap pages.
#include "tools/heap_pages.hpp"

#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>

namespace canopy {

/// Whether OpenMP's waits are left to canopy: neither OMP_WAIT_POLICY nor GOMP_SPINCOUNT is set.
inline bool waits_unset() { return !std::getenv("OMP_WAIT_POLICY") && !std::getenv("GOMP_SPINCOUNT"); }

/// What the commands that run parallel work get, for `canopy info`.
inline std::string waits_described() {
  if (waits_unset()) return "passive in stand, detect, sweep, light and render";
  std::string set;
  for (const char* name : {"OMP_WAIT_POLICY", "GOMP_SPINCOUNT"})
    if (const char* v = std::getenv(name)) set += (set.empty() ? "" : ", ") + std::string(name) + "=" + v;
  return "as set: " + set;
}

/// Whether canopy's command line runs parallel work (the commands that grow, detect, resolve,
/// light or render a stand).
inline bool command_runs_parallel(int argc, char** argv) {
  if (argc < 2) return false;
  const std::string_view c = argv[1];
  return c == "stand" || c == "detect" || c == "sweep" || c == "light" || c == "render";
}

/// Runs this program again (the same arguments, the environment plus glibc.malloc.hugetlb=1 where
/// `pages` is large and the machine can give them, plus OMP_WAIT_POLICY=passive where
/// `passive_waits` and waits_unset()) when either applies, unless this process is such a rerun or
/// runs under valgrind. Returns only when it does not run itself again (the exec failing
/// included: the run goes on as it was). Call first thing in main, before threads, MPI or the GPU.
inline void rerun_for_run(HeapPages pages, bool passive_waits, char** argv) {
  if (std::getenv("CANOPY_RERUN")) return;
  if (const char* preload = std::getenv("LD_PRELOAD"); preload && std::strstr(preload, "vgpreload")) return;
  if (access("/proc/self/exe", X_OK) != 0) return;
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  const std::string before = tunables ? tunables : "";
  const bool large = pages == HeapPages::large && before.find("glibc.malloc.hugetlb") == std::string::npos &&
                     heap_pages_possible();
  const bool passive = passive_waits && waits_unset();
  if (!large && !passive) return;
  if (large)
    setenv("GLIBC_TUNABLES",
           (before.empty() ? std::string() : before + ":").append("glibc.malloc.hugetlb=1").c_str(), 1);
  if (passive) setenv("OMP_WAIT_POLICY", "passive", 1);
  setenv("CANOPY_RERUN", "1", 1);
  execv("/proc/self/exe", argv);
  // Not run again: as we were.
  if (large) {
    if (tunables) setenv("GLIBC_TUNABLES", before.c_str(), 1);
    else unsetenv("GLIBC_TUNABLES");
  }
  if (passive) unsetenv("OMP_WAIT_POLICY");
  unsetenv("CANOPY_RERUN");
}

}  // namespace canopy
