#pragma once
/// The memory a run may still take: MemAvailable from /proc/meminfo (what the kernel can hand out
/// without swapping), or 0 where it cannot be read; and what the process holds.
#include <cstddef>
#include <fstream>
#include <string>

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

/// The process's resident memory (/proc/self/statm), or 0 where it cannot be read.
inline std::size_t resident_memory() {
  std::ifstream in("/proc/self/statm");
  std::size_t pages = 0, resident = 0;
  if (!(in >> pages >> resident)) return 0;
  return resident * static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
}

}  // namespace canopy
