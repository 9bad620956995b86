#pragma once
/// Standard output is part of a command's result (`canopy detect`'s table, `canopy info`, each
/// summary): a run whose output could not be written fails, as `canopy derive` alone did (exit 1;
/// `canopy detect DIR > /dev/full` exited 0 with its table lost). And a descriptor 0-2 that a
/// caller closed (`canopy stand ... >&-`) is held by /dev/null opened read-only before anything
/// else opens a file: otherwise the first file canopy opened would take descriptor 1 and receive
/// what the run prints, and with /dev/null read-only a write to it fails as a closed one would.
#include <fcntl.h>
#include <unistd.h>

#include <fmt/format.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace canopy::cli {

/// First thing in main: descriptors 0, 1 and 2 open (see above).
inline void hold_standard_descriptors() {
  for (int fd = 0; fd <= 2; ++fd)
    if (::fcntl(fd, F_GETFD) == -1 && errno == EBADF) {
      const int got = ::open("/dev/null", O_RDONLY);  // the lowest free descriptor: fd
      if (got >= 0 && got != fd) ::close(got);
    }
}

/// `rc`, or 1 with a message when it was 0 and standard output could not be written.
inline int checked_output(int rc) {
  const bool flush_failed = std::fflush(stdout) != 0;
  const int err = errno;
  if ((flush_failed || std::ferror(stdout)) && rc == 0) {
    fmt::print(stderr, "canopy: error: writing standard output failed{}{}\n", flush_failed ? ": " : "",
               flush_failed ? std::strerror(err) : "");
    return 1;
  }
  return rc;
}

}  // namespace canopy::cli
