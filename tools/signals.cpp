#include "tools/signals.hpp"

#include "geometry/run_files.hpp"

#include <fmt/format.h>

#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>
#include <string>
#include <pthread.h>
#include <thread>
#include <unistd.h>

namespace canopy::cli {
namespace {

std::atomic<bool> g_thread_started{false};
std::atomic<std::atomic<bool>*> g_soft{nullptr};  // SoftInterrupt's flag while one lives

/// The signals taken: those not ignored when the program started (a shell runs a script's
/// background jobs with SIGINT ignored, nohup ignores SIGHUP: left as they were).
sigset_t handled() {
  sigset_t set;
  sigemptyset(&set);
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction now {};
    if (sigaction(sig, nullptr, &now) == 0 && now.sa_handler != SIG_IGN) sigaddset(&set, sig);
  }
  return set;
}

[[noreturn]] void end_by(int sig) {
  (void)lock_run_paths()
      .release();  // kept: a run moving its folder into place finishes first, and nothing changes after
  const std::vector<std::string> removed = remove_run_paths();
  std::string what = removed.empty() ? std::string("no unfinished files to remove")
                                     : "removed this run's unfinished output:";
  for (std::size_t i = 0; i < removed.size() && i < 4; ++i) what += (i ? ", " : " ") + removed[i];
  if (removed.size() > 4) what += fmt::format(" and {} more", removed.size() - 4);
  std::fflush(stdout);
  fmt::print(stderr, "canopy: stopped by {}: {}\n",
             sig == SIGINT    ? "SIGINT"
             : sig == SIGTERM ? "SIGTERM"
                              : "SIGHUP",
             what);
  std::fflush(stderr);
  std::signal(sig, SIG_DFL);
  sigset_t one;
  sigemptyset(&one);
  sigaddset(&one, sig);
  pthread_sigmask(SIG_UNBLOCK, &one, nullptr);
  std::raise(sig);
  _exit(128 + sig);
}

extern "C" void soft_handler(int) {
  if (std::atomic<bool>* f = g_soft.load()) f->store(true);
  std::signal(SIGINT, SIG_DFL);  // a second Ctrl-C stops at once
}

}  // namespace

void end_on_terminate() {
  // Nothing here allocates where it can help it: the handler may run for an out-of-memory error,
  // and an exception thrown from it would end the process in a second terminate, silently.
  std::set_terminate([] {
    // Nothing may leave the handler either (the runtime then aborts without a word: it did for
    // two threads out of memory at once under `ulimit -v`), hence a catch around each step.
    const char* what = nullptr;  // points into the exception, which `e` keeps alive
    const std::exception_ptr e = std::current_exception();
    if (e) {
      try {
        std::rethrow_exception(e);
      } catch (const std::bad_alloc&) {
        what = "out of memory";
      } catch (const std::exception& x) {
        what = x.what();
      } catch (...) {
        what = "an unknown exception";
      }
    }
    try {
      (void)lock_run_paths().release();  // kept: nothing changes on disk after the clean-up
      remove_run_paths();
    } catch (...) {
      // the list of what was removed could not be made; what could be removed was
    }
    std::fflush(stdout);
    std::fputs("canopy: error: ", stderr);
    std::fputs(what && *what ? what : "internal error (terminated)", stderr);
    std::fputs("\n", stderr);
    std::fflush(stderr);
    if (!what || !*what) std::abort();
    _exit(1);
  });
}

void start_signal_thread() {
  if (g_thread_started.exchange(true)) return;
  // A file-size limit (ulimit -f) killed the process by SIGXFSZ without a word, leaving its
  // temporary files: ignored, a write past it fails with EFBIG and the run ends as any write
  // error does (one line, its files removed).
  std::signal(SIGXFSZ, SIG_IGN);
  const sigset_t set = handled();
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
  std::thread([set] {
    bool soft_used = false;
    for (;;) {
      int sig = 0;
      if (sigwait(&set, &sig) != 0) continue;
      if (sig == SIGINT && !soft_used) {
        if (std::atomic<bool>* f = g_soft.load()) {
          f->store(true);
          soft_used = true;
          continue;
        }
      }
      end_by(sig);
    }
  }).detach();
}

SoftInterrupt::SoftInterrupt(std::atomic<bool>& flag) {
  g_soft = &flag;
  if (!g_thread_started) std::signal(SIGINT, soft_handler);
}

SoftInterrupt::~SoftInterrupt() {
  if (!g_thread_started) std::signal(SIGINT, SIG_DFL);
  g_soft = nullptr;
}

}  // namespace canopy::cli
