#pragma once
/// canopy's programs run with glibc's heap in transparent huge pages (2 MiB): resolution's
/// candidates and working lists, allocated by many threads, are first touched page by page,
/// and with 4 KiB pages those faults cost about a tenth of a 10,000-plant resolution on the
/// 16-core H100 machine (0.987-1.001 s against 0.890-0.903 s, alternated on one loan;
/// bench/results/README.md, "Heap and pages"). glibc reads that setting (the tunable
/// glibc.malloc.hugetlb, glibc 2.35 and later; older ones ignore it) only from the environment
/// at start-up, so a program without GLIBC_TUNABLES starts itself again, once, with it set.
/// GLIBC_TUNABLES already set (the user's own settings, or this second start) or
/// CANOPY_HUGE_PAGES=0 leave everything as it is, and so does a failed restart.
#include <cstdlib>
#include <cstring>

#if defined(__linux__) && defined(__GLIBC__)
#include <unistd.h>
#endif

namespace canopy {

/// Call first in main(), before any thread or file is opened (argv as main() got it).
inline void use_huge_page_heap(char** argv) {
#if defined(__linux__) && defined(__GLIBC__)
  if (std::getenv("GLIBC_TUNABLES")) return;
  if (const char* v = std::getenv("CANOPY_HUGE_PAGES"); v && std::strcmp(v, "0") == 0) return;
  // Under valgrind the restart would leave it (it follows exec only when told to).
  if (const char* pre = std::getenv("LD_PRELOAD"); pre && std::strstr(pre, "vgpreload")) return;
  if (setenv("GLIBC_TUNABLES", "glibc.malloc.hugetlb=1", 1) != 0) return;
  execv("/proc/self/exe", argv);
  unsetenv("GLIBC_TUNABLES");  // not started again: go on with the heap as it is
#else
  (void)argv;
#endif
}

}  // namespace canopy
