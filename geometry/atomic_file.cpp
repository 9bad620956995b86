#include "geometry/atomic_file.hpp"
#include "geometry/write_all.hpp"

#include "geometry/folder_ops.hpp"
#include "geometry/run_files.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <filesystem>
#include <new>
#include <stdexcept>
#include <unistd.h>

namespace canopy {
namespace {

namespace fs = std::filesystem;

/// The temporary name of `path` before its process tag: "NAME.tmp-", NAME shortened as a staging
/// folder's is (a name of 230 bytes and more would pass the 255 a file name may have).
std::string temporary_prefix(const std::string& path) {
  const fs::path p(path);
  return (p.parent_path() / (folder_ops::staging_stem(p.filename().string()) + ".tmp-")).string();
}

/// Removes "NAME.tmp-TAG" beside `path` where TAG names a process that has ended.
void remove_dead_temporaries(const std::string& path) {
  const fs::path p(path);
  const std::string prefix = fs::path(temporary_prefix(path)).filename().string();
  std::error_code ec;
  const fs::path folder = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.starts_with(prefix) && is_dead_temporary(name)) fs::remove(it->path(), ec);
  }
}

/// Where a write of `path` goes: a symbolic link's target (the link stays), followed through up
/// to 40 links.
std::string link_target(const std::string& path) {
  fs::path p(path);
  std::error_code ec;
  for (int hops = 0; hops < 40 && fs::is_symlink(p, ec); ++hops) {
    const fs::path to = fs::read_symlink(p, ec);
    if (ec) break;
    p = to.is_absolute() ? to : p.parent_path() / to;
  }
  return p.string();
}

}  // namespace

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  // What is there and is not a regular file (a FIFO, a device), and any name under /dev or /proc
  // whatever it leads to (/dev/stdout redirected to a file is that file), is appended to in place:
  // a rename would replace it. A folder is refused; a symbolic link's target is replaced, the link
  // stays.
  struct stat st;
  if (::stat(path_.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) throw std::runtime_error(fmt::format("cannot write {}: it is a folder", path_));
    if (!S_ISREG(st.st_mode) || path_.starts_with("/dev/") || path_.starts_with("/proc/")) {
      direct_ = true;
      // Appended: /dev/stdout opened anew with "wb" would cut a file the shell appends to.
      f_ = std::fopen(path_.c_str(), "ab");
      if (!f_) throw std::runtime_error(fmt::format("cannot write {}: {}", path_, std::strerror(errno)));
      return;
    }
  }
  path_ = link_target(path_);
  remove_dead_temporaries(path_);
  tmp_ = temporary_prefix(path_) + process_tag();
  const auto lock = lock_run_paths();  // registered before it exists: a signal's clean-up sees it
  registered_ = register_run_path(tmp_, RunPath::file);
  f_ = std::fopen(tmp_.c_str(), "wb");
  if (!f_) {
    const std::string reason = std::strerror(errno);
    unregister_run_path(registered_);
    throw std::runtime_error(fmt::format("cannot write {} (its temporary {}): {}", path_, tmp_, reason));
  }
  std::setvbuf(f_, nullptr, _IOFBF, 1 << 20);
}

AtomicFile::AtomicFile(std::string path, Direct) : path_(std::move(path)), direct_(true) {
  f_ = std::fopen(path_.c_str(), "wb");
  if (!f_) throw std::runtime_error(fmt::format("cannot write {}: {}", path_, std::strerror(errno)));
  std::setvbuf(f_, nullptr, _IOFBF, 1 << 20);
}

AtomicFile::AtomicFile(int fd, std::string path, Unnamed)
    : path_(std::move(path)), direct_(true), unnamed_(true) {
  f_ = ::fdopen(fd, "wb");
  if (!f_) {
    const std::string reason = std::strerror(errno);
    ::close(fd);
    throw std::runtime_error(fmt::format("cannot write {}: {}", path_, reason));
  }
  std::setvbuf(f_, nullptr, _IOFBF, 1 << 20);
}

AtomicFile::~AtomicFile() {
  if (f_) std::fclose(f_);
  if (!committed_ && !direct_) std::remove(tmp_.c_str());
  unregister_run_path(registered_);
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
    if (std::fflush(f_) != 0)
      throw std::runtime_error(fmt::format("writing {} failed: {}", path_, std::strerror(errno)));
    const std::size_t block = n;
    const off_t at = ::lseek(fileno(f_), 0, SEEK_CUR);
    if (const int error = write_all(fileno(f_), data, n))
      throw std::runtime_error(fmt::format("writing {} failed: {}", path_, std::strerror(error)));
    // The block's write-back starts now, while the next is formatted: the sync before the folder
    // is swapped in then finds little left to write (a hint only; the sync decides).
    if (at >= 0) ::sync_file_range(fileno(f_), at, static_cast<off_t>(block), SYNC_FILE_RANGE_WRITE);
    return;
  }
  if (n && std::fwrite(data, 1, n, f_) != n)
    throw std::runtime_error(fmt::format("writing {} failed: {}", path_, std::strerror(errno)));
}

void AtomicFile::sync() {
  if (!f_) return;
  const auto t = std::chrono::steady_clock::now();
  const bool bad = std::fflush(f_) != 0 || std::ferror(f_) != 0 || ::fsync(fileno(f_)) != 0;
  const int err = errno;
  const double s = seconds_since(t);
  times_.busy_s += s, times_.waited_s += s;
  if (bad) throw std::runtime_error(fmt::format("writing {} failed: {}", path_, std::strerror(err)));
}

void AtomicFile::close() {
  if (!f_) return;
  const auto t = std::chrono::steady_clock::now();
  bool bad = std::fflush(f_) != 0 || std::ferror(f_) != 0;
  // A file renamed into place is synced first, so a crash after the rename finds it whole.
  if (!direct_ && !bad) bad = ::fsync(fileno(f_)) != 0;
  const int err = errno;
  const int rc = std::fclose(f_);
  const double s = seconds_since(t);
  times_.busy_s += s, times_.waited_s += s;
  f_ = nullptr;
  if (bad || rc != 0)
    throw std::runtime_error(fmt::format("writing {} failed: {}", path_, std::strerror(bad ? err : errno)));
}

void AtomicFile::commit() {
  close();
  if (direct_) return;
  if (std::rename(tmp_.c_str(), path_.c_str()) != 0)
    throw std::runtime_error(fmt::format("cannot rename {} to {}: {}", tmp_, path_, std::strerror(errno)));
  committed_ = true;
  unregister_run_path(registered_);
  registered_ = 0;
  const fs::path folder = fs::path(path_).parent_path();
  const int fd = ::open(folder.empty() ? "." : folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
}

OutputSet::OutputSet(const std::string& dir, std::vector<std::string> replaces, std::string marker)
    : folder_(dir, std::move(replaces), std::move(marker)) {}

AtomicFile& OutputSet::open(const std::string& name) {
  names_.reserve(names_.size() + 1);
  files_.reserve(files_.size() + 1);
  std::string final_path = folder_.dir() + "/" + name;
  if (const int fd = folder_.unnamed_file(); fd >= 0) {
    // Nothing may throw between the open and the file's owner: the constructor owns fd even when
    // it throws; only the allocation before it can fail without it.
    std::unique_ptr<AtomicFile> f(new (std::nothrow)
                                      AtomicFile(fd, std::move(final_path), AtomicFile::Unnamed{}));
    if (!f) {
      ::close(fd);
      throw std::bad_alloc();
    }
    files_.push_back(std::move(f));  // room reserved above
  } else {
    // Under the registry's lock: once a signal's clean-up holds it, no file appears in the
    // staging folder behind its back.
    const std::string path = folder_.path(name);
    const auto lock = lock_run_paths();
    files_.push_back(std::make_unique<AtomicFile>(path, AtomicFile::Direct{}));
  }
  names_.push_back(name);
  return *files_.back();
}

WriteTimes OutputSet::times() const {
  WriteTimes sum = closed_;
  for (const auto& f : files_) sum += f->times();
  return sum;
}

StagedFolder::Committed OutputSet::commit_all() {
  // Every file complete and on disk before any gets a name: the staging folder appears only
  // once all are synced, so that a SIGKILL leaves it behind only in the milliseconds of linking
  // and swapping (synced one by one between links, the window was the whole sync, a second or
  // more for a 100-plant stand on the 2-core machine's disk).
  for (const auto& f : files_)
    if (f->unnamed()) f->sync();
  for (std::size_t i = 0; i < files_.size(); ++i)
    if (files_[i]->unnamed()) folder_.link_in(fileno(files_[i]->get()), names_[i]);
  for (auto& f : files_) f->close();
  for (const auto& f : files_) closed_ += f->times();
  files_.clear();
  names_.clear();
  return folder_.commit();
}

}  // namespace canopy
