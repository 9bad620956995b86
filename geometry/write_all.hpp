#pragma once
/// Writes all of a block to a file descriptor, again after a signal interrupts a write.
#include <cerrno>
#include <cstddef>

#include <unistd.h>

namespace canopy {

/// 0 once all `n` bytes are written, else the error that stopped it (EIO for a write that took
/// nothing); how much was written before then is the caller's to undo.
inline int write_all(int fd, const void* data, std::size_t n) {
  const char* p = static_cast<const char*>(data);
  while (n > 0) {
    const ssize_t w = ::write(fd, p, n);
    if (w < 0 && errno == EINTR) continue;
    if (w < 0) return errno;
    if (w == 0) return EIO;
    p += w;
    n -= static_cast<std::size_t>(w);
  }
  return 0;
}

}  // namespace canopy
