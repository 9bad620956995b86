#include "geometry/atomic_file.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <unistd.h>

namespace canopy {

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  tmp_ = fmt::format("{}.tmp-{}", path_, ::getpid());
  f_ = std::fopen(tmp_.c_str(), "wb");
  if (!f_) throw std::runtime_error(fmt::format("cannot write {}: {}", tmp_, std::strerror(errno)));
  std::setvbuf(f_, nullptr, _IOFBF, 1 << 20);
}

AtomicFile::AtomicFile(std::string path, Direct) : path_(std::move(path)), direct_(true) {
  f_ = std::fopen(path_.c_str(), "wb");
  if (!f_) throw std::runtime_error(fmt::format("cannot write {}: {}", path_, std::strerror(errno)));
  std::setvbuf(f_, nullptr, _IOFBF, 1 << 20);
}

AtomicFile::~AtomicFile() {
  if (f_) std::fclose(f_);
  if (!committed_ && !direct_) std::remove(tmp_.c_str());
}

namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

void AtomicFile::write(const void* data, std::size_t n) {
  const auto t = std::chrono::steady_clock::now();
  write_raw(data, n);
  const double s = seconds_since(t);
  times_.busy_s += s, times_.waited_s += s;
}

void AtomicFile::write_behind(std::string_view text) {
  const auto t = std::chrono::steady_clock::now();
  write_raw(text.data(), text.size());
  times_.busy_s += seconds_since(t);
}

void AtomicFile::write_raw(const void* data, std::size_t n) {
  times_.bytes += n;
  if (n >= (std::size_t(1) << 16)) {
    // Large blocks go straight to the kernel: no second copy through stdio's buffer.
    if (std::fflush(f_) != 0) throw std::runtime_error(fmt::format("writing {} failed: {}", path_, std::strerror(errno)));
    const char* p = static_cast<const char*>(data);
    while (n > 0) {
      const ssize_t w = ::write(fileno(f_), p, n);
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0) throw std::runtime_error(fmt::format("writing {} failed: {}", path_, std::strerror(errno)));
      p += w;
      n -= static_cast<std::size_t>(w);
    }
    return;
  }
  if (n && std::fwrite(data, 1, n, f_) != n)
    throw std::runtime_error(fmt::format("writing {} failed: {}", path_, std::strerror(errno)));
}

void AtomicFile::close() {
  if (!f_) return;
  const auto t = std::chrono::steady_clock::now();
  const bool bad = std::ferror(f_) != 0;
  const int rc = std::fclose(f_);
  const double s = seconds_since(t);
  times_.busy_s += s, times_.waited_s += s;
  f_ = nullptr;
  if (bad || rc != 0) throw std::runtime_error(fmt::format("writing {} failed: {}", path_, std::strerror(errno)));
}

void AtomicFile::commit() {
  close();
  if (direct_) return;
  if (std::rename(tmp_.c_str(), path_.c_str()) != 0)
    throw std::runtime_error(fmt::format("cannot rename {} to {}: {}", tmp_, path_, std::strerror(errno)));
  committed_ = true;
}

OutputSet::OutputSet(std::string dir) : dir_(std::move(dir)) {}

AtomicFile& OutputSet::open(const std::string& name) {
  files_.push_back(std::make_unique<AtomicFile>((std::filesystem::path(dir_) / name).string()));
  return *files_.back();
}

WriteTimes OutputSet::times() const {
  WriteTimes sum;
  for (const auto& f : files_) sum += f->times();
  return sum;
}

void OutputSet::commit_all() {
  for (auto& f : files_) f->close();  // every file complete before any is renamed
  for (auto& f : files_) f->commit();
}

void prepare_output_dir(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error(fmt::format("cannot create the output folder {}: {}", dir, ec.message()));
  AtomicFile probe((std::filesystem::path(dir) / ".canopy-write-test").string());
  probe.close();  // destroyed uncommitted: removed
}

}  // namespace canopy
