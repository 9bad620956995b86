#pragma once
/// SIGINT, SIGTERM and SIGHUP for the canopy command (docs/design.md "Output folders and
/// failures"). Those not ignored at the start (a script's background jobs ignore SIGINT; nohup,
/// SIGHUP) are blocked in every thread and taken by one thread of their own with
/// sigwait, so the clean-up runs as ordinary code, never inside a signal handler: it removes what
/// the run has on disk that is not in place (geometry/run_files.hpp: temporary files, the staging
/// folder, folders made for the output), says so on standard error, and ends the process by the
/// same signal (exit status 128 + its number). A run that is moving its folder into place
/// finishes that first, so the folder is the earlier one or the new one, never a mix.
#include <atomic>

namespace canopy::cli {

/// Call once at the start of main, before any other thread is started (they inherit the mask),
/// after anything that runs the program again (tools/heap_pages.hpp).
void start_signal_thread();

/// An exception that cannot be thrown on (one leaving a parallel region or a thread) ends the
/// command as an error does, not with an abort: what the run has on disk that is not in place is
/// removed, `canopy: error: out of memory` (or the exception's message) is printed and the exit
/// status is 1. A std::terminate without an exception removes the same and aborts.
void end_on_terminate();

/// While one lives, the first SIGINT sets `flag` instead of ending the run (canopy sweep ends
/// after the run in progress); a second SIGINT, or SIGTERM, ends the run at once. Without the
/// signal thread (the Python module keeps its host's handlers) it installs a plain handler.
class SoftInterrupt {
 public:
  explicit SoftInterrupt(std::atomic<bool>& flag);
  ~SoftInterrupt();
  SoftInterrupt(const SoftInterrupt&) = delete;
  SoftInterrupt& operator=(const SoftInterrupt&) = delete;
};

}  // namespace canopy::cli
