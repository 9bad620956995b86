#pragma once
/// Reading a file a user names (a grammar, a positions file, a stand folder's tables, a sweep's
/// runs.csv and sweep.json) with limits: only a regular file is read (a folder, /dev/zero, a pipe
/// or a terminal is refused at once instead of being read for ever), no more than a documented
/// number of bytes, and lines no longer than a bound, so a file without line breaks never grows
/// one line to the size of the disk.
#include "geometry/layout.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

namespace canopy {

/// What canopy reads at most from each kind of file (docs/cli.md, "Limits and refusals").
inline constexpr std::uint64_t kMaxGrammarBytes = std::uint64_t{16} << 20;    // 16 MiB
inline constexpr std::uint64_t kMaxPositionsBytes = std::uint64_t{1} << 30;   // 1 GiB
inline constexpr std::uint64_t kMaxPlantsCsvBytes = std::uint64_t{1} << 30;   // 1 GiB
inline constexpr std::uint64_t kMaxOrgansCsvBytes = std::uint64_t{64} << 30;  // 64 GiB
inline constexpr std::uint64_t kMaxRunsCsvBytes = std::uint64_t{1} << 30;     // 1 GiB
inline constexpr std::uint64_t kMaxSweepJsonBytes = std::uint64_t{1} << 20;   // 1 MiB
inline constexpr std::uint64_t kMaxReportBytes = std::uint64_t{64} << 20;     // 64 MiB (report.json)
/// The longest line a CSV input may have (canopy writes lines of a few hundred bytes; a grammar
/// path in a positions file is at most PATH_MAX).
inline constexpr std::size_t kMaxCsvLineBytes = 64 << 10;  // 64 KiB

/// A file refused by InputFile; what() is "PATH: REASON" (or "PATH:LINE: REASON").
class InputRefused : public std::invalid_argument {
 public:
  InputRefused(const std::string& path, int line, const std::string& reason)
      : std::invalid_argument(line > 0 ? fmt::format("{}:{}: {}", path, line, reason)
                                       : fmt::format("{}: {}", path, reason)),
        line_(line), reason_(reason) {}
  int line() const { return line_; }
  const std::string& reason() const { return reason_; }

 private:
  int line_ = 0;
  std::string reason_;
};

/// A file named by the user, opened for reading. The constructor throws FileNotFound when it
/// cannot be opened ("PATH: cannot open the WHAT") and InputRefused ("PATH: the WHAT is not a
/// regular file", "... is larger than N bytes") otherwise; reading throws InputRefused when the
/// file turns out longer than the limit (a file under /proc says size 0) or a line longer than its
/// bound.
class InputFile {
 public:
  InputFile(const std::string& path, std::string_view what, std::uint64_t max_bytes);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  /// The next line, without its '\n' (or "\r\n"); false at the end of the file. `max_line` bounds it;
  /// a carriage return inside a line (an old Mac file's line end) or a NUL byte is refused.
  bool next_line(std::string& line, std::size_t max_line = kMaxCsvLineBytes);
  /// Takes lines with NUL bytes as they are (a reader that drops a torn last line: a file
  /// appended to when the machine lost power may end in NULs).
  void keep_nul_bytes() { keep_nul_ = true; }
  /// Lines read so far (the number of the line next_line gave last).
  int line_number() const { return line_; }
  /// The rest of the file.
  std::string read_all();
  const std::string& path() const { return path_; }

 private:
  /// Refills the buffer; false at the end of the file.
  bool fill();
  /// Counts the line `line` just taken, drops its "\r" end and refuses one left inside, or a NUL
  /// byte; true.
  bool take_line(std::string& line);
  std::string old_mac_lines() const;

  std::string path_, what_;
  std::uint64_t max_bytes_ = 0, read_ = 0;
  int fd_ = -1;
  int line_ = 0;
  bool keep_nul_ = false;
  std::string buf_;
  std::size_t at_ = 0;
};

/// The whole of a file named by the user, with InputFile's checks.
std::string read_input_file(const std::string& path, std::string_view what, std::uint64_t max_bytes);

}  // namespace canopy
