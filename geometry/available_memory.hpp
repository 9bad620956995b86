#pragma once
/// The memory a run may still take: MemAvailable from /proc/meminfo (what the kernel can hand out
/// without swapping), or 0 where it cannot be read; and what the process holds.
#include <cstddef>
#include <cstdio>
#include <fstream>
#include <string>

#include <fcntl.h>
#include <unistd.h>

namespace canopy {

inline std::size_t memory_available() {
  std::ifstream in("/proc/meminfo");
  std::string key, unit;
  std::size_t kb = 0;
  while (in >> key >> kb >> unit)
    if (key == "MemAvailable:") return kb * 1024;
  return 0;
}

/// The process's resident memory (/proc/self/statm), or 0 where it cannot be read. Read into a
/// buffer on the stack: it is asked when memory runs short (a stream would allocate).
inline std::size_t resident_memory() {
  const int fd = ::open("/proc/self/statm", O_RDONLY | O_CLOEXEC);
  if (fd < 0) return 0;
  char text[128];
  const ssize_t n = ::read(fd, text, sizeof text - 1);
  ::close(fd);
  if (n <= 0) return 0;
  text[n] = '\0';
  unsigned long long pages = 0, resident = 0;
  if (std::sscanf(text, "%llu %llu", &pages, &resident) != 2) return 0;
  return static_cast<std::size_t>(resident) * static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
}

}  // namespace canopy
