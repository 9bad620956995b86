#pragma once
/// The memory a run may still take, and what the process holds. The machine's MemAvailable from
/// /proc/meminfo (what the kernel can hand out without swapping) is not what a process in a
/// container or under a batch system's limit may take: the smallest of it, the room under the
/// memory control groups' limits (memory_detail::cgroup_room) and the address-space limit
/// (`ulimit -v`) less the process's size is; 0 where none can be read. Past the limit of a control
/// group the kernel kills the process; past the address-space limit allocations fail, both without
/// the clear refusal a budget gives.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include <fcntl.h>
#include <sys/resource.h>
#include <unistd.h>

namespace canopy {

/// A size for a message: "2.4 GB", or "87 MB" below 1 GB (where "0.0 GB" said nothing).
inline std::string memory_text(double bytes) {
  char buf[48];
  if (bytes >= 1e9) std::snprintf(buf, sizeof buf, "%.1f GB", bytes / 1e9);
  else std::snprintf(buf, sizeof buf, "%.0f MB", bytes / 1e6);
  return buf;
}

namespace memory_detail {

/// The first number of file `path` (false where it cannot be read or is "max").
inline bool read_number(const std::string& path, std::uint64_t& out) {
  std::ifstream in(path);
  return static_cast<bool>(in >> out);
}

/// The value of `key` in a memory.stat file (0 where absent).
inline std::uint64_t stat_value(const std::string& path, const std::string& key) {
  std::ifstream in(path);
  std::string k;
  std::uint64_t v = 0;
  while (in >> k >> v)
    if (k == key) return v;
  return 0;
}

/// What the process's memory control group lets it still take (~0: no limit found): the least
/// room over its group and the groups above it, up to the mount's root (a limit is often set on
/// a parent: a Slurm job above its steps, a systemd slice above its scopes; a container sees its
/// own group at the root). A group's room is its limit less what it holds besides file pages
/// (the page cache, which the kernel reclaims before it kills).
inline std::uint64_t cgroup_room() {
  std::uint64_t room = ~std::uint64_t{0};
  std::ifstream groups("/proc/self/cgroup");
  std::string line;
  while (std::getline(groups, line)) {
    const std::size_t a = line.find(':'), b = a == std::string::npos ? a : line.find(':', a + 1);
    if (b == std::string::npos) continue;
    const std::string controllers = line.substr(a + 1, b - a - 1), path = line.substr(b + 1);
    const bool v2 = controllers.empty() && line.compare(0, a, "0") == 0;
    bool v1 = false;
    std::stringstream list(controllers);
    for (std::string c; std::getline(list, c, ',');) v1 = v1 || c == "memory";
    if (!v1 && !v2) continue;
    const std::string base = v2 ? "/sys/fs/cgroup" : "/sys/fs/cgroup/memory";
    std::string dir = base + (path == "/" ? std::string() : path);
    for (;;) {
      std::uint64_t limit = 0, used = 0;
      // v2 writes "max" where there is no limit (not read as a number); v1 a number near 2^63.
      if (read_number(dir + (v2 ? "/memory.max" : "/memory.limit_in_bytes"), limit) &&
          limit < (std::uint64_t{1} << 60) &&
          read_number(dir + (v2 ? "/memory.current" : "/memory.usage_in_bytes"), used)) {
        const std::uint64_t files = stat_value(dir + "/memory.stat", v2 ? "file" : "total_cache");
        const std::uint64_t held = used > files ? used - files : 0;
        room = std::min(room, limit > held ? limit - held : 0);
      }
      if (dir.size() <= base.size()) break;
      dir.erase(dir.rfind('/'));
    }
  }
  return room;
}

/// The process's size and resident memory in bytes (/proc/self/statm's first two fields); false
/// where they cannot be read. Read into a buffer on the stack: resident_memory is asked when
/// memory runs short (a stream would allocate).
inline bool statm(std::uint64_t& size, std::uint64_t& resident) {
  const int fd = ::open("/proc/self/statm", O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  char text[128];
  const ssize_t n = ::read(fd, text, sizeof text - 1);
  ::close(fd);
  if (n <= 0) return false;
  text[n] = '\0';
  unsigned long long pages = 0, held = 0;
  if (std::sscanf(text, "%llu %llu", &pages, &held) != 2) return false;
  const auto page = static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
  size = pages * page, resident = held * page;
  return true;
}

/// What the address-space limit lets the process still map (~0: none).
inline std::uint64_t address_space_room() {
  rlimit r{};
  if (::getrlimit(RLIMIT_AS, &r) != 0 || r.rlim_cur == RLIM_INFINITY) return ~std::uint64_t{0};
  std::uint64_t size = 0, resident = 0;
  if (!statm(size, resident)) return ~std::uint64_t{0};
  return r.rlim_cur > size ? r.rlim_cur - size : 0;
}

}  // namespace memory_detail

inline std::size_t memory_available() {
  std::ifstream in("/proc/meminfo");
  std::string key, unit;
  std::size_t kb = 0;
  std::uint64_t avail = 0;
  while (in >> key >> kb >> unit)
    if (key == "MemAvailable:") {
      avail = std::uint64_t{kb} * 1024;
      break;
    }
  if (avail == 0) return 0;
  avail = std::min({avail, memory_detail::cgroup_room(), memory_detail::address_space_room()});
  return static_cast<std::size_t>(std::max<std::uint64_t>(avail, 1));  // 0 says "unknown"
}

/// The process's resident memory (/proc/self/statm), or 0 where it cannot be read.
inline std::size_t resident_memory() {
  std::uint64_t size = 0, resident = 0;
  return memory_detail::statm(size, resident) ? static_cast<std::size_t>(resident) : 0;
}

}  // namespace canopy
