#pragma once
/// The heap in 2 MiB pages for runs on the GPU. A CUDA resolution of 10,000 plants plans on all
/// the host's cores from hundreds of thousands of small lists (candidates, their neighbours and
/// pairs, each level's groups); in 4 KiB pages that is about 190,000 page faults a run. glibc
/// (2.35 and later) asks the kernel for transparent huge pages on its heap when the tunable
/// glibc.malloc.hugetlb=1 is set, which it reads only when a process starts: so a program that
/// wants it sets the tunable and runs itself again, once, before doing anything else
/// (tools/process_rerun.hpp).
///
/// On a 16-core GPU machine large pages take the planning's page faults from about 190,000 to
/// a few thousand and make the 10,000-plant CUDA resolution faster (bench_resolve, alternated
/// runs); the CPU backend there is alike or faster. On a small VM, whose huge-page faults cost
/// more system time than small ones, the CPU backend's resolutions are slower. Hence the
/// default: large pages where the run uses the GPU, small ones otherwise.
/// CANOPY_HEAP_PAGES=large or =small in the environment overrides the choice.
#include <fmt/format.h>
#include <gnu/libc-version.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <string_view>

namespace canopy {

enum class HeapPages { small, large };

/// CANOPY_HEAP_PAGES if set to "large" or "small", else `gpu_run ? large : small`; throws
/// std::invalid_argument when it is set to anything else.
inline HeapPages heap_pages_for(bool gpu_run) {
  if (const char* v = std::getenv("CANOPY_HEAP_PAGES"); v && *v) {  // set empty: as unset
    if (!std::strcmp(v, "large")) return HeapPages::large;
    if (!std::strcmp(v, "small")) return HeapPages::small;
    // A misspelt value was passed over and the run took the default unannounced.
    throw std::invalid_argument(fmt::format(
        "CANOPY_HEAP_PAGES='{}' is neither 'large' nor 'small' (unset it for canopy's own choice)", v));
  }
  return gpu_run ? HeapPages::large : HeapPages::small;
}

/// Whether this machine can give the heap large pages, the three things a rerun for them needs
/// (tools/process_rerun.hpp):
/// the kernel offers transparent huge pages (its setting can be read and is not [never]; where
/// /sys is not mounted it cannot, and the pages stay small), glibc reads the tunable (2.35 and
/// later), and the program can run itself again (/proc/self/exe). tests/tools/test_cli_stand.sh
/// asks the same three questions, so program and test decide alike on any machine.
inline bool heap_pages_possible() {
  int major = 0, minor = 0;
  if (std::sscanf(gnu_get_libc_version(), "%d.%d", &major, &minor) != 2 || major < 2 ||
      (major == 2 && minor < 35))
    return false;
  if (access("/proc/self/exe", X_OK) != 0) return false;
  std::ifstream thp("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string modes;
  return std::getline(thp, modes) && modes.find("[never]") == std::string::npos;
}

/// Whether the machine has an NVIDIA GPU's device files: what `--backend auto` would run on.
inline bool gpu_device_files() { return access("/dev/nvidiactl", F_OK) == 0; }

/// "large" where this process runs with glibc.malloc.hugetlb=1 on a machine that can give them,
/// else "small" (for reports).
inline const char* heap_pages_in_use() {
  const char* t = std::getenv("GLIBC_TUNABLES");
  return t && std::strstr(t, "glibc.malloc.hugetlb=1") && heap_pages_possible() ? "large" : "small";
}

/// Whether a command line runs on the GPU: a backend option ("--backend X", "--backend=X",
/// "--backends X,Y") naming cuda, or naming none or auto (`default_backend`'s meaning then)
/// where the machine has an NVIDIA GPU.
inline bool command_runs_on_gpu(int argc, char** argv, std::string_view default_backend) {
  std::string_view backend = default_backend;
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    for (std::string_view name : {"--backend", "--backends"}) {
      if (a == name && i + 1 < argc) backend = argv[i + 1];
      else if (a.size() > name.size() && a.substr(0, name.size()) == name && a[name.size()] == '=')
        backend = a.substr(name.size() + 1);
    }
  }
  if (backend.find("cuda") != std::string_view::npos) return true;
  return backend.find("auto") != std::string_view::npos && gpu_device_files();  // auto, or a list naming it
}

}  // namespace canopy
