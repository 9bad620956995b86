#pragma once
/// The process's resident peak stage by stage: Linux keeps the high-water mark of resident memory
/// (VmHWM in /proc/self/status) and resets it to the current size when "5" is written to
/// /proc/self/clear_refs, so a stage's peak is the mark read at its end after a reset at its
/// start. The reset lowers the maxrss that getrusage and wait4 report as well (they count from
/// the last reset), so the marks are kept before each reset: process_peak_bytes is the peak since
/// the process started. Where /proc lacks either (not Linux, or a restricted container) peaks read 0 and the
/// report leaves them out.
#include <atomic>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

namespace canopy::cli {

/// The high-water mark of resident memory in bytes (0 where unknown).
inline std::uint64_t peak_memory_bytes() {
  std::ifstream in("/proc/self/status");
  std::string key;
  std::uint64_t kb = 0;
  while (in >> key) {
    if (key == "VmHWM:") return (in >> kb) ? kb * 1024 : 0;
    in.ignore(4096, '\n');
  }
  return 0;
}

/// The largest high-water mark seen before a reset, process-wide (bytes).
inline std::atomic<std::uint64_t> peak_before_resets{0};

/// Resets the high-water mark to what is resident now, first keeping the mark it had in
/// peak_before_resets; false where the kernel refuses.
inline bool reset_peak_memory() {
  const std::uint64_t mark = peak_memory_bytes();
  std::uint64_t kept = peak_before_resets.load();
  while (mark > kept && !peak_before_resets.compare_exchange_weak(kept, mark)) {
  }
  std::FILE* f = std::fopen("/proc/self/clear_refs", "w");
  if (!f) return false;
  const bool ok = std::fputs("5", f) >= 0;
  return std::fclose(f) == 0 && ok;
}

/// The process's resident peak since it started, resets included (bytes; 0 where unknown).
inline std::uint64_t process_peak_bytes() {
  const std::uint64_t now = peak_memory_bytes();
  const std::uint64_t kept = peak_before_resets.load();
  return now > kept ? now : kept;
}

/// Measures one stage: construct at its start, read at its end (GB, 0 where unknown).
class StagePeak {
 public:
  StagePeak() : reset_(reset_peak_memory()) {}
  double gb() const { return reset_ ? static_cast<double>(peak_memory_bytes()) / 1e9 : 0.0; }

 private:
  bool reset_;
};

}  // namespace canopy::cli
