#pragma once
/// How a command's process ends once its work is done and its files are in place. Freeing a large
/// stand and tearing down a GPU's context cost a run time its user waits for and gains nothing
/// from: the kernel takes the memory back, and the driver the device's, when the process is gone.
/// So a command ends the process at once (std::_Exit, after flushing its output) and leaves its
/// stand to it (leave_to_process_end); canopy stand also frees its backend and destroys
/// the GPU's context (cuda::reset_device) on a thread of its own while its files are written
/// (tools/stand_run.cpp), since the driver's part of a process's end takes its time whether the
/// process frees or not. bench_stand --backend cuda on an H100 machine, from the files' commit to
/// the process's end (`end_s`, single runs): 0.119 / 0.156 s at 1,000 / 10,000 plants freeing
/// everything, 0.111 / 0.145 s with _Exit alone; in another run 0.118 / 0.205 s with _Exit alone
/// and 0.050 / 0.148 s with the context destroyed during the export (the CPU backend's 1,000
/// plants: 0.019 s). Not done:
/// - under mpirun (every rank must reach MPI_Finalize);
/// - in a build with AddressSanitizer or LeakSanitizer (their leak check runs at a normal exit);
/// - with CANOPY_FREE_AT_EXIT set to anything but 0 (a leak checker such as valgrind, a profiler
///   that flushes its data at exit).
#include <cstdio>
#include <cstdlib>
#include <string_view>
#include <type_traits>
#include <utility>

namespace canopy {

/// Whether a process may end without freeing (see above); `under_mpi`: launched by mpirun.
inline bool quick_process_end(bool under_mpi = false) {
#if defined(__SANITIZE_ADDRESS__)
  return false;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(leak_sanitizer)
  return false;
#endif
#endif
  if (under_mpi) return false;
  const char* v = std::getenv("CANOPY_FREE_AT_EXIT");
  return !(v && *v && std::string_view(v) != "0");
}

/// Ends the process with status `rc` now when quick_process_end(under_mpi), output flushed;
/// returns `rc` otherwise, for the caller to return from main.
inline int end_process(int rc, bool under_mpi = false) {
  if (!quick_process_end(under_mpi)) return rc;
  std::fflush(nullptr);
  std::_Exit(rc);
}

/// Moves `object` where nothing frees it, for a caller whose process ends by end_process right
/// after (a stand of millions of organs); where the process will end normally
/// (quick_process_end() false) it is freed here, as its owner would have.
template <class T>
void leave_to_process_end(T&& object) {
  using Held = std::decay_t<T>;
  if (!quick_process_end()) {
    Held freed_now(std::forward<T>(object));
    return;
  }
  [[maybe_unused]] const Held* left = new Held(std::forward<T>(object));
}

}  // namespace canopy
