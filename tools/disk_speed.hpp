#pragma once
/// The write speed of the disk a benchmark writes its files to, measured the way the exports
/// write (large write(2) calls), so an export's speed can be told as a fraction of the disk's.
#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace canopy {

struct DiskSpeed {
  double written_gbs = 0;  // bytes / time of the write calls (into the page cache, mostly)
  double synced_gbs = 0;   // bytes / time of the writes and the fsync that puts them on the disk
};

/// Writes `bytes` (rounded up to 4 MiB blocks of non-repeating data) to a new file in `dir`,
/// syncs it and removes it.
inline DiskSpeed measure_disk(const std::string& dir, std::uint64_t bytes) {
  constexpr std::size_t kBlock = std::size_t(4) << 20;
  std::vector<std::uint64_t> block(kBlock / 8);
  std::uint64_t x = 0x9e3779b97f4a7c15ULL;
  for (auto& w : block) w = x = x * 6364136223846793005ULL + 1442695040888963407ULL;  // not compressible
  const std::string path = dir + "/.disk-speed-probe";
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) throw std::runtime_error("cannot write " + path);
  const auto t0 = std::chrono::steady_clock::now();
  std::uint64_t done = 0;
  bool ok = true;
  while (ok && done < bytes) {
    block[0] = done;  // every block differs
    const char* p = reinterpret_cast<const char*>(block.data());
    for (std::size_t left = kBlock; ok && left > 0;) {
      const ssize_t w = ::write(fd, p, left);
      ok = w > 0;
      if (ok) p += w, left -= static_cast<std::size_t>(w);
    }
    done += kBlock;
  }
  const auto t1 = std::chrono::steady_clock::now();
  ok = ok && ::fsync(fd) == 0;
  const auto t2 = std::chrono::steady_clock::now();
  ::close(fd);
  ::unlink(path.c_str());
  if (!ok) throw std::runtime_error("writing " + path + " failed");
  const auto gbs = [&](auto a, auto b) {
    return static_cast<double>(done) / 1e9 / std::chrono::duration<double>(b - a).count();
  };
  return {gbs(t0, t1), gbs(t0, t2)};
}

}  // namespace canopy
