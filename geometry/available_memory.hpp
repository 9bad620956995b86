#pragma once
/// The memory a run may still take: MemAvailable from /proc/meminfo (what the kernel can hand out
/// without swapping), or 0 where it cannot be read.
#include <cstddef>
#include <fstream>
#include <string>

namespace canopy {

inline std::size_t memory_available() {
  std::ifstream in("/proc/meminfo");
  std::string key, unit;
  std::size_t kb = 0;
  while (in >> key >> kb >> unit)
    if (key == "MemAvailable:") return kb * 1024;
  return 0;
}

}  // namespace canopy
