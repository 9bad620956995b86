#pragma once
/// Small operations on folders that the staged folder's two ways of committing share
/// (geometry/staged_folder.cpp, geometry/staged_in_place.cpp): open folders, their entries, syncs
/// and the names of staging folders.
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>
#include <dirent.h>

#include "geometry/fnv1a.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

namespace canopy::folder_ops {

/// A staging folder's name is ".NAME" + kStagingMark + "PID-START-K" beside the output, or
/// kStagingMark + "PID-START-K" inside it when the output is committed in place.
inline constexpr const char* kStagingMark = ".canopy-";

/// The NAME part of a staging folder beside output NAME: NAME itself, or for a name too long to
/// take the ~45 bytes a staging name adds within a name's 255 (a folder named with 226 or more
/// bytes could not be written), its first 163 bytes, '~' and 16 hex digits of a hash of the whole
/// name, so that two long names that begin alike keep apart. The run and the next run's clean-up
/// name it alike.
inline std::string staging_stem(const std::string& name) {
  constexpr std::size_t kKeep = 163;
  if (name.size() <= kKeep + 17) return name;
  return name.substr(0, kKeep) + fmt::format("~{:016x}", fnv1a(name));
}

inline std::string why() { return std::strerror(errno); }

/// The refusal of a commit whose files were made from a folder (or stand) that another run
/// replaced meanwhile (StagedFolder::require_folder), the same for both ways of committing.
inline std::runtime_error replaced_meanwhile(const std::string& dir) {
  return std::runtime_error(
      dir + " was replaced by another run while this one read it; nothing of this run was written (run it "
            "again on the folder as it is now)");
}

/// An open folder, closed on scope exit.
struct Fd {
  int fd = -1;
  explicit Fd(const std::string& path, int flags = O_RDONLY | O_DIRECTORY | O_CLOEXEC)
      : fd(::open(path.c_str(), flags)) {}
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
};

/// A run's turn at moving files into a folder in place: the folder's flock, held until the
/// object goes (or the process ends, however it ends). Taken without blocking, retried every 20
/// ms, so that the signal thread can end the run meanwhile; after `patience` seconds (the lock
/// held that long by something that is not a canopy run moving files, such as flock(1) around
/// this very command) the run goes on without it and says so in `note`. A file system without
/// locks: no turn, as before.
class FolderTurn {
 public:
  FolderTurn(int folder_fd, const std::string& named, std::string& note, double patience = 10)
      : fd_(folder_fd) {
    const auto start = std::chrono::steady_clock::now();
    for (;;) {
      if (::flock(fd_, LOCK_EX | LOCK_NB) == 0) return;
      if (errno != EWOULDBLOCK && errno != EINTR) break;  // no locks here
      if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > patience) {
        note = fmt::format(
            "{} has been locked for {:g} s by something that is not moving a stand in; moved "
            "the files in without waiting for it",
            named, patience);
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    fd_ = -1;
  }
  ~FolderTurn() {
    if (fd_ >= 0) ::flock(fd_, LOCK_UN);
  }
  FolderTurn(const FolderTurn&) = delete;
  FolderTurn& operator=(const FolderTurn&) = delete;

 private:
  int fd_;
};

/// The names in folder `path` ("." and ".." left out); empty when it cannot be read.
inline std::vector<std::string> names_in(const std::string& path) {
  std::vector<std::string> out;
  if (DIR* d = ::opendir(path.c_str())) {
    while (const dirent* e = ::readdir(d))
      if (std::strcmp(e->d_name, ".") && std::strcmp(e->d_name, "..")) out.emplace_back(e->d_name);
    ::closedir(d);
  }
  std::sort(out.begin(), out.end());
  return out;
}

inline bool is_folder_at(int dirfd, const std::string& name) {
  struct stat st;
  return ::fstatat(dirfd, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 && S_ISDIR(st.st_mode);
}

inline bool exists_at(int dirfd, const std::string& name) {
  struct stat st;
  return ::fstatat(dirfd, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0;
}

inline bool same_file_at(int dira, int dirb, const std::string& name) {
  struct stat a, b;
  return ::fstatat(dira, name.c_str(), &a, AT_SYMLINK_NOFOLLOW) == 0 &&
         ::fstatat(dirb, name.c_str(), &b, AT_SYMLINK_NOFOLLOW) == 0 && a.st_dev == b.st_dev &&
         a.st_ino == b.st_ino;
}

inline void sync_folder(const std::string& path) {
  Fd d(path);
  if (d.fd >= 0) ::fsync(d.fd);
}

/// The part after ".NAME.canopy-" of a staging name: "PID-START-K" or "PID-START-K-old"; the
/// tag ("PID-START") when it is one, else empty.
inline std::string staging_tag(std::string_view rest) {
  if (rest.ends_with("-old")) rest.remove_suffix(4);
  int dashes = 0;
  for (char c : rest) {
    if (c == '-') ++dashes;
    else if (c < '0' || c > '9') return {};
  }
  if (dashes != 2 || rest.front() == '-' || rest.back() == '-' || rest.find("--") != std::string_view::npos)
    return {};
  return std::string(rest.substr(0, rest.rfind('-')));
}

/// In a staging folder inside its output (a folder committed in place): the files are being moved
/// in; its lines name the files to remove once they are.
inline constexpr const char* kCommitList = ".canopy-commit";

/// A staging folder inside an output folder committed in place: its name (kStagingMark +
/// "PID-START-K") and its run's tag ("PID-START").
struct InPlaceStaging {
  std::string name, tag;
};

/// The staging folders inside `dir` whose names carry a run's tag: what a reader waits for while
/// their run lives, and what the next run finishes or removes once it is dead.
inline std::vector<InPlaceStaging> in_place_stagings(const std::string& dir) {
  std::vector<InPlaceStaging> out;
  const std::size_t mark = std::strlen(kStagingMark);
  for (std::string& e : names_in(dir)) {
    if (!e.starts_with(kStagingMark)) continue;
    std::string tag = staging_tag(std::string_view(e).substr(mark));
    if (!tag.empty()) out.push_back({std::move(e), std::move(tag)});
  }
  return out;
}

}  // namespace canopy::folder_ops
