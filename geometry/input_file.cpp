#include "geometry/input_file.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <stdexcept>
#include <sys/stat.h>
#include <unistd.h>

namespace canopy {
namespace {

/// A limit as it is documented: "16 MiB", "64 KiB", "1 GiB".
std::string size_text(std::uint64_t n) {
  if (n >= (std::uint64_t{1} << 30) && n % (std::uint64_t{1} << 30) == 0)
    return fmt::format("{} GiB", n >> 30);
  if (n >= (std::uint64_t{1} << 20) && n % (std::uint64_t{1} << 20) == 0)
    return fmt::format("{} MiB", n >> 20);
  if (n >= (std::uint64_t{1} << 10) && n % (std::uint64_t{1} << 10) == 0)
    return fmt::format("{} KiB", n >> 10);
  return fmt::format("{} bytes", n);
}

}  // namespace

InputFile::InputFile(const std::string& path, std::string_view what, std::uint64_t max_bytes)
    : path_(path), what_(what), max_bytes_(max_bytes) {
  // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer, for ever.
  fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd_ < 0) throw FileNotFound(fmt::format("{}: cannot open the {}", path, what_));
  struct stat st {};
  std::string refusal;
  if (::fstat(fd_, &st) != 0) refusal = fmt::format("cannot read the {} ({})", what_, std::strerror(errno));
  else if (S_ISDIR(st.st_mode)) refusal = fmt::format("the {} is a folder, not a file", what_);
  else if (!S_ISREG(st.st_mode))
    refusal = fmt::format("the {} is not a regular file (a device, pipe or socket)", what_);
  else if (static_cast<std::uint64_t>(st.st_size) > max_bytes_)
    refusal = fmt::format("the {} is larger than the {} canopy reads ({} bytes)", what_,
                          size_text(max_bytes_), st.st_size);
  if (!refusal.empty()) {
    ::close(fd_);
    fd_ = -1;
    throw InputRefused(path, 0, refusal);
  }
  const int flags = ::fcntl(fd_, F_GETFL);
  if (flags >= 0) ::fcntl(fd_, F_SETFL, flags & ~O_NONBLOCK);
}

InputFile::~InputFile() {
  if (fd_ >= 0) ::close(fd_);
}

bool InputFile::fill() {
  buf_.erase(0, at_);
  at_ = 0;
  char chunk[1 << 16];
  ssize_t n;
  do n = ::read(fd_, chunk, sizeof chunk);
  while (n < 0 && errno == EINTR);
  if (n < 0)
    throw std::runtime_error(fmt::format("{}: cannot read the {} ({})", path_, what_, std::strerror(errno)));
  if (n == 0) return false;
  read_ += static_cast<std::uint64_t>(n);
  if (read_ > max_bytes_)
    throw InputRefused(
        path_, 0, fmt::format("the {} is larger than the {} canopy reads", what_, size_text(max_bytes_)));
  buf_.append(chunk, static_cast<std::size_t>(n));
  return true;
}

bool InputFile::next_line(std::string& line, std::size_t max_line) {
  std::size_t scanned = at_;
  for (;;) {
    const std::size_t nl = buf_.find('\n', scanned);
    if (nl != std::string::npos) {
      if (nl - at_ > max_line) break;
      line.assign(buf_, at_, nl - at_);
      at_ = nl + 1;
      return take_line(line);
    }
    if (buf_.size() - at_ > max_line) break;
    scanned = buf_.size() - at_;  // fill() moves the unread part to the front
    if (!fill()) {
      if (at_ == buf_.size()) return false;
      line.assign(buf_, at_, std::string::npos);  // a last line without '\n'
      at_ = buf_.size();
      return take_line(line);
    }
  }
  if (buf_.find('\r', at_) != std::string::npos) throw InputRefused(path_, line_ + 1, old_mac_lines());
  throw InputRefused(
      path_, line_ + 1,
      fmt::format("a line of the {} is longer than the {} canopy reads", what_, size_text(max_line)));
}

bool InputFile::take_line(std::string& line) {
  ++line_;
  if (!line.empty() && line.back() == '\r') line.pop_back();  // a file with Windows line ends
  // A carriage return left inside: lines ended by one alone (an old Mac format) read as one long
  // line, whose first cells would be taken for a header running into the rows.
  if (line.find('\r') != std::string::npos) throw InputRefused(path_, line_, old_mac_lines());
  // A NUL byte (a binary or damaged file) would also cut every message quoting the line there.
  if (const std::size_t nul = keep_nul_ ? std::string::npos : line.find('\0'); nul != std::string::npos)
    throw InputRefused(
        path_, line_,
        fmt::format("column {}: a NUL byte, which no text file holds (the {} is binary or damaged)", nul + 1,
                    what_));
  return true;
}

std::string InputFile::old_mac_lines() const {
  return fmt::format(
      "the {}'s lines end with a carriage return alone (an old Mac format); save the file with \\n or "
      "\\r\\n line ends",
      what_);
}

std::string InputFile::read_all() {
  while (fill()) {
  }
  std::string rest = buf_.substr(at_);
  at_ = buf_.size();
  return rest;
}

std::string read_input_file(const std::string& path, std::string_view what, std::uint64_t max_bytes) {
  InputFile f(path, what, max_bytes);
  return f.read_all();
}

}  // namespace canopy
