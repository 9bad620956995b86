#include "geometry/staged_folder.hpp"

#include "geometry/folder_ops.hpp"
#include "geometry/run_files.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <dirent.h>
#include <fcntl.h>
#include <filesystem>
#include <stdexcept>
#include <tuple>
#include <sys/stat.h>
#include <sys/vfs.h>
#include <unistd.h>

namespace canopy {
namespace {

namespace fs = std::filesystem;

using namespace folder_ops;

std::atomic<unsigned> g_staging_count{0};

/// "/proc/self/fd/N": the path through which an open file, unnamed ones too, can be linked.
struct ProcFd {
  char path[32];
  explicit ProcFd(int fd) { std::snprintf(path, sizeof path, "/proc/self/fd/%d", fd); }
};

/// The process's umask, read once from /proc/self/status (umask() would set it to read it, which
/// other threads could see); -1 where it cannot be read.
int process_umask() {
  static const int mask = [] {
    std::FILE* f = std::fopen("/proc/self/status", "r");
    if (!f) return -1;
    char line[256];
    int m = -1;
    while (std::fgets(line, sizeof line, f))
      if (std::strncmp(line, "Umask:", 6) == 0) {
        m = static_cast<int>(std::strtol(line + 6, nullptr, 8));
        break;
      }
    std::fclose(f);
    return m;
  }();
  return mask;
}

}  // namespace

FolderIdentity folder_identity(const std::string& dir, const std::string& file) {
  struct stat st {};
  if (::stat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) return {};
  FolderIdentity id{static_cast<std::uint64_t>(st.st_dev), static_cast<std::uint64_t>(st.st_ino), 0};
  if (!file.empty() && ::stat((dir + "/" + file).c_str(), &st) == 0) id.file_ino = st.st_ino;
  return id;
}

void open_in_one_set(const std::string& dir, const std::vector<std::string>& paths,
                     const std::function<void()>& open_all) {
  // The folder (its change time too: a folder made after the one read may get its inode
  // number), and each file: a run writing the folder in place replaces the files, not the folder.
  const auto identity = [&] {
    std::vector<std::int64_t> id(4 + paths.size(), 0);
    struct stat st {};
    if (::stat(dir.c_str(), &st) == 0)
      id[0] = static_cast<std::int64_t>(st.st_dev), id[1] = static_cast<std::int64_t>(st.st_ino),
      id[2] = st.st_ctim.tv_sec, id[3] = st.st_ctim.tv_nsec;
    for (std::size_t i = 0; i < paths.size(); ++i)
      if (::stat(paths[i].c_str(), &st) == 0) id[4 + i] = static_cast<std::int64_t>(st.st_ino);
    return id;
  };
  // A live run moving its files in (geometry/staged_in_place.cpp): its list is in its staging
  // folder inside `dir` until the last file is in.
  const auto moving_in = [&] {
    for (const InPlaceStaging& e : in_place_stagings(dir)) {
      struct stat st {};
      if (!tag_is_dead(e.tag) && ::stat((dir + "/" + e.name + "/" + kCommitList).c_str(), &st) == 0) return true;
    }
    return false;
  };
  for (int attempt = 0, waits = 0; attempt < 16;) {
    if (waits < 2000 && moving_in()) {
      ++waits;
      ::usleep(1000);
      continue;
    }
    const auto before = identity();
    open_all();
    if (identity() == before && (waits >= 2000 || !moving_in())) return;
    ++attempt;
  }
}

void open_in_one_set(const std::string& dir, const std::vector<std::ifstream*>& files,
                     const std::vector<std::string>& paths) {
  open_in_one_set(dir, paths, [&] {
    for (std::size_t i = 0; i < files.size(); ++i) {
      files[i]->close();
      files[i]->clear();
      files[i]->open(paths[i], std::ios::binary);
    }
  });
}

bool is_dead_temporary(const std::string& name) {
  if (name == ".canopy-write-test") return true;  // an earlier version's probe
  // An earlier version's MPI files: "X.tmp-mpi" and its ranks' spill files "X.tmp-mpi.rankN".
  if (name.find(".tmp-mpi") != std::string::npos) return true;
  const std::size_t at = name.rfind(".tmp-");
  return at != std::string::npos && at > 0 && tag_is_dead(std::string_view(name).substr(at + 5));
}

std::string output_folder(const std::string& dir) {
  if (dir.empty()) throw std::runtime_error("cannot create the output folder: no folder named");
  // The folder the kernel names: "L/../Z" with L a link into another folder is that folder's
  // sibling, not ./Z (read as text, a run replaced ./Z while readers followed the link). The
  // existing part of the path is resolved (links, "..", "."), the rest taken as written.
  std::error_code ec;
  fs::path p = fs::weakly_canonical(fs::absolute(dir), ec);
  if (ec) p = fs::absolute(dir).lexically_normal();  // a loop of links: named as written
  if (p.filename().empty()) p = p.parent_path();
  // A link to what is not a folder stays itself, and is refused as a file is.
  if (const fs::path named = fs::absolute(dir).lexically_normal();
      fs::is_symlink(named, ec) && !fs::is_directory(p, ec))
    p = named;
  if (p == p.root_path() || p.filename().empty() || p.filename() == "..")
    throw std::runtime_error(
        fmt::format("cannot create the output folder {}: the file system's root cannot be replaced", dir));
  return p.string();
}

namespace {

/// Whether folder `p` (`st` its lstat) is the root of a mount: another device than its parent's,
/// or, for a bind mount of the same file system (a container's volume), what statx says.
bool is_mount_root(const fs::path& p, const struct stat& st) {
  struct stat parent;
  if (::stat(p.parent_path().c_str(), &parent) == 0 && parent.st_dev != st.st_dev) return true;
#ifdef STATX_ATTR_MOUNT_ROOT
  struct statx sx;
  if (::statx(AT_FDCWD, p.c_str(), AT_SYMLINK_NOFOLLOW, 0, &sx) == 0 &&
      (sx.stx_attributes_mask & STATX_ATTR_MOUNT_ROOT))
    return (sx.stx_attributes & STATX_ATTR_MOUNT_ROOT) != 0;
#endif
  return false;  // a kernel before 5.8 does not say: a bind mount's rename then fails (EBUSY)
}

/// Whether removing the name of a file held open on the file system of folder `fd` only drops the
/// name (the blocks freed at the last close): local file systems. NFS, SMB and FUSE clients
/// instead rename such a file to a hidden name (.nfsXXXX) in the folder, which would then not be
/// empty; there the files are removed by name.
bool frees_on_close(int fd) {
  struct statfs fs;
  if (fd < 0 || ::fstatfs(fd, &fs) != 0) return false;
  switch (static_cast<unsigned long>(fs.f_type)) {
    case 0x6969UL:      // NFS
    case 0xFF534D42UL:  // CIFS
    case 0xFE534D42UL:  // SMB2
    case 0x517BUL:      // SMB
    case 0x65735546UL:  // FUSE
    case 0x01021997UL:  // 9P
    case 0x5346414FUL:  // AFS
      return false;
    default: return true;
  }
}

/// Where the staging folder for output folder `p` (`dir` as named) can be made: `p`'s parent, or
/// its nearest existing ancestor for a new folder. Throws when `p` cannot be replaced as a whole.
/// Where the staging folder of output `p` goes: beside it, or inside it when the folder must stay
/// the same folder (`in_place`): the working folder (a shell in it would be left in a removed
/// folder) or a mount point (which cannot be renamed).
fs::path staging_place(const fs::path& p, const std::string& dir, bool* in_place = nullptr) {
  const auto refuse = [&](const std::string& reason) {
    throw std::runtime_error(fmt::format("cannot create the output folder {}: {}", dir, reason));
  };
  if (in_place) *in_place = false;
  struct stat st;
  if (::lstat(p.c_str(), &st) == 0) {
    if (S_ISLNK(st.st_mode)) {
      // output_folder() follows a link to a folder: one left here leads nowhere.
      struct stat target;
      const bool there = ::stat(p.c_str(), &target) == 0;
      const bool loop = !there && errno == ELOOP;
      std::error_code ec;
      const std::string to = fs::read_symlink(p, ec).string();
      if (loop) refuse("it is a symbolic link in a loop of links");
      refuse(there ? fmt::format("it is a symbolic link to {}, which is not a folder", to)
                   : fmt::format("it is a symbolic link to {}, which is not there (make that folder, or "
                                 "remove the link)",
                                 to));
    }
    if (!S_ISDIR(st.st_mode)) refuse("it exists and is not a folder");
    struct stat here;
    const bool working = ::stat(".", &here) == 0 && here.st_dev == st.st_dev && here.st_ino == st.st_ino;
    const bool mount = is_mount_root(p, st);
    if (working || mount) {
      if (in_place) *in_place = true;
      return p;
    }
    return p.parent_path();
  }
  if (errno != ENOENT && errno != ENOTDIR) refuse(why());
  fs::path at = p.parent_path();
  while (::lstat(at.c_str(), &st) != 0 && at != at.root_path()) at = at.parent_path();
  if (::stat(at.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
    refuse(fmt::format("{} is not a folder", at.string()));
  return at;
}

}  // namespace

void check_output_dir(const std::string& dir) {
  const fs::path writable = staging_place(output_folder(dir), dir);
  const auto refuse = [&](const std::string& reason) {
    throw std::runtime_error(fmt::format("cannot create the output folder {}: {}", dir, reason));
  };
  // A folder made and removed again: what the staging folder will need.
  const fs::path probe = writable / fmt::format(".canopy-probe-{}", process_tag());
  if (::mkdir(probe.c_str(), 0700) != 0)
    refuse(fmt::format("cannot make a folder in {}: {}", writable.string(), why()));
  ::rmdir(probe.c_str());
}

StagedFolder::StagedFolder(const std::string& dir, std::vector<std::string> replaces, std::string marker)
    : replaces_(std::move(replaces)), marker_(std::move(marker)) {
  try {
    open(dir);
  } catch (...) {
    // No destructor runs for a constructor that throws: the folders made so far go here.
    for (auto it = created_.rbegin(); it != created_.rend(); ++it) ::rmdir(it->c_str());
    for (std::uint64_t id : created_ids_) unregister_run_path(id);
    throw;
  }
}

void StagedFolder::open(const std::string& dir) {
  dir_ = output_folder(dir);
  named_ = dir;
  const fs::path p(dir_);
  base_ = staging_place(p, dir, &in_place_).string();
  parent_ = p.parent_path().string();
  name_ = p.filename().string();
  remove_leftovers();
  finish_in_place_leftovers();
  // The set's names are its files': a folder under one (which a file of the set could not
  // replace, nothing being removed recursively) is refused before any work, in both ways of
  // committing, whether this run writes that file or not.
  for (const std::string& n : replaces_) {
    struct stat st;
    if (::lstat((p / n).c_str(), &st) == 0 && S_ISDIR(st.st_mode))
      throw std::runtime_error(
          fmt::format("cannot write the output folder {}: {} is a folder there, under the name of one of the "
                      "folder's files; move or rename it",
                      named_, n));
  }
  staging_ = in_place_ ? fmt::format("{}/{}{}-{}", dir_, kStagingMark, process_tag(), g_staging_count++)
                       : fmt::format("{}/.{}{}{}-{}", parent_, staging_stem(name_), kStagingMark,
                                     process_tag(), g_staging_count++);
}

void StagedFolder::make() {
  if (made_) return;
  const auto lock = lock_run_paths();
  // The folders missing above the output, made now and removed again if the run fails.
  const fs::path p(dir_);
  std::vector<fs::path> missing;
  for (fs::path a = p.parent_path(); !fs::exists(fs::symlink_status(a)) && a != a.root_path();
       a = a.parent_path())
    missing.push_back(a);
  for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
    if (::mkdir(it->c_str(), 0777) == 0) {
      created_.push_back(it->string());
      created_ids_.push_back(register_run_path(it->string(), RunPath::created_folder));
    } else if (errno != EEXIST) {
      throw std::runtime_error(
          fmt::format("cannot create the output folder {}: cannot make {}: {}", named_, it->string(), why()));
    }
  }
  if (::mkdir(staging_.c_str(), 0777) != 0)
    throw std::runtime_error(
        fmt::format("cannot create the output folder {}: cannot make {}: {}", named_, staging_, why()));
  staging_id_ = register_run_path(staging_, RunPath::staging);
  made_ = true;
}

std::string StagedFolder::path(const std::string& name) {
  make();
  return staging_ + "/" + name;
}

int StagedFolder::unnamed_file() const {
  // O_TMPFILE: on a file system without it (or a kernel before 3.11) the open fails, and the
  // files are written under their names in the staging folder instead. Linking one in later
  // goes through /proc/self/fd, which must be there.
  const int fd = ::open(base_.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
  if (fd < 0) return -1;
  if (::access(ProcFd(fd).path, F_OK) != 0) {
    ::close(fd);
    return -1;
  }
  // Kernels before 6.0 left the umask off O_TMPFILE files on file systems without POSIX ACLs:
  // the mode a named file would get (0666 less the umask) is set here.
  if (const int mask = process_umask(); mask >= 0) ::fchmod(fd, 0666 & ~static_cast<mode_t>(mask));
  return fd;
}

bool StagedFolder::unnamed_file_possible() const {
  const int fd = unnamed_file();
  if (fd < 0) return false;
  ::close(fd);
  return true;
}

void StagedFolder::link_in(int fd, const std::string& name) {
  make();
  const auto lock = lock_run_paths();  // no file appears behind a signal's clean-up
  const std::string to = staging_ + "/" + name;
  if (::linkat(AT_FDCWD, ProcFd(fd).path, AT_FDCWD, to.c_str(), AT_SYMLINK_FOLLOW) != 0)
    throw std::runtime_error(fmt::format("cannot write {}: {}", to, why()));
  linked_.push_back(name);
}

StagedFolder::~StagedFolder() {
  if (committed_) return;
  const auto lock = lock_run_paths();
  if (made_) remove_flat_folder(staging_);
  unregister_run_path(staging_id_);
  for (auto it = created_.rbegin(); it != created_.rend(); ++it) ::rmdir(it->c_str());
  for (std::uint64_t id : created_ids_) unregister_run_path(id);
}

void StagedFolder::remove_leftovers() {
  // ".NAME.canopy-TAG-K" of a process that has ended: an unfinished new set (the run died before
  // its swap; things of the user's it carried across are put back), or the earlier set after the
  // swap; "...-old" the earlier folder where renames stood in for the exchange.
  std::string prefix = ".";
  prefix.append(staging_stem(name_)).append(kStagingMark);
  std::vector<std::string> dead;
  for (const std::string& e : names_in(parent_)) {
    if (!e.starts_with(prefix)) continue;
    const std::string tag = staging_tag(std::string_view(e).substr(prefix.size()));
    if (!tag.empty() && tag_is_dead(tag)) dead.push_back(e);
  }
  // An earlier folder moved aside goes back first when the folder itself is missing.
  std::stable_partition(dead.begin(), dead.end(), [](const std::string& e) { return e.ends_with("-old"); });
  for (const std::string& e : dead) {
    const std::string path = parent_ + "/" + e;
    struct stat st;
    if (e.ends_with("-old") && ::lstat(dir_.c_str(), &st) != 0 && ::rename(path.c_str(), dir_.c_str()) == 0) {
      leftovers_.push_back(e + " (put back as " + name_ + ")");
      continue;
    }
    Fd from(path), to(dir_);
    std::vector<std::string> kept;
    for (const std::string& n : names_in(path)) {
      const bool folder = is_folder_at(from.fd, n);
      const bool ours = !folder && (std::find(replaces_.begin(), replaces_.end(), n) != replaces_.end() ||
                                    is_dead_temporary(n));
      if (ours || (to.fd >= 0 && same_file_at(from.fd, to.fd, n))) {
        ::unlinkat(from.fd, n.c_str(), 0);
      } else if (to.fd >= 0 && !exists_at(to.fd, n) &&
                 ::renameat(from.fd, n.c_str(), to.fd, n.c_str()) == 0) {
        // carried across by that run and not yet in place: back where it was
      } else {
        kept.push_back(n);
      }
    }
    if (::rmdir(path.c_str()) == 0) leftovers_.push_back(e);
    else
      leftover_notes_.push_back(fmt::format(
          "kept {}, left by an earlier run into {} (one that was killed, or that kept it for what it could "
          "not move back): it holds {} (not canopy's, and not the same as in {})",
          path, named_, fmt::join(kept, ", "), dir_));
  }
}

StagedFolder::Committed StagedFolder::commit() {
  make();  // a set of no files is an empty folder
  Committed out;
  // Every file's data on disk, then the folder's entries: a crash after the swap finds whole files.
  // Files linked in were synced before they had a name (OutputSet::commit_all): syncing them
  // again would only lengthen the time the staging folder stands under a name.
  for (const std::string& n : names_in(staging_)) {
    if (std::find(linked_.begin(), linked_.end(), n) != linked_.end()) continue;
    const std::string f = path(n);
    struct stat st;
    if (::lstat(f.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) continue;
    Fd file(f, O_RDONLY | O_CLOEXEC);
    if (file.fd < 0 || ::fsync(file.fd) != 0)
      throw std::runtime_error(fmt::format("cannot sync {}: {}", f, why()));
  }
  sync_folder(staging_);

  if (in_place_) return commit_in_place();
  auto lock = lock_run_paths();  // a signal now waits until the folder is swapped and registered as such
  struct stat st;
  const bool earlier = ::lstat(dir_.c_str(), &st) == 0;
  std::string old_path;  // where the earlier folder is once the new one is in place
  // The folder that fd `at` is (with its required file) is not the one the files were made from.
  const auto is_another = [&](int at) {
    struct stat now {};
    if (!required_ || at < 0 || ::fstat(at, &now) != 0) return required_.has_value();
    FolderIdentity id{static_cast<std::uint64_t>(now.st_dev), static_cast<std::uint64_t>(now.st_ino), 0};
    if (!required_file_.empty() && ::fstatat(at, required_file_.c_str(), &now, 0) == 0) id.file_ino = now.st_ino;
    return !(id == *required_);
  };
  if (required_ && !(folder_identity(dir_, required_file_) == *required_)) throw replaced_meanwhile(dir_);
  // A folder without the marker holds no earlier set: files of those names are the user's.
  bool earlier_set = true;
  const auto in_earlier_set = [&](const std::string& n) {
    return earlier_set && std::find(replaces_.begin(), replaces_.end(), n) != replaces_.end();
  };
  // The earlier files the new set writes again, by inode: a file saved under such a name
  // between the listing and the swap is not one of them.
  std::vector<std::pair<std::string, ino_t>> superseded;
  const auto still_superseded = [&](int dirfd, const std::string& n) {
    struct stat now;
    if (::fstatat(dirfd, n.c_str(), &now, AT_SYMLINK_NOFOLLOW) != 0) return false;
    for (const auto& [name, ino] : superseded)
      if (name == n) return ino == now.st_ino;
    return false;
  };
  if (!earlier) {
    if (::rename(staging_.c_str(), dir_.c_str()) != 0)
      throw std::runtime_error(fmt::format("cannot move {} to {}: {}", staging_, dir_, why()));
    unregister_run_path(staging_id_);
    staging_id_ = 0;
  } else {
    if (!S_ISDIR(st.st_mode))
      throw std::runtime_error(fmt::format("cannot replace {}: it is not a folder", dir_));
    Fd old_fd(dir_), new_fd(staging_);
    if (old_fd.fd < 0 || new_fd.fd < 0)
      throw std::runtime_error(fmt::format("cannot open {} or {}: {}", dir_, staging_, why()));
    earlier_set = marker_.empty() || exists_at(old_fd.fd, marker_);
    // A folder under the name of a new file would go with the earlier folder, and be removed with
    // it: found before anything is carried across (the run then fails with the folder as it was).
    for (const std::string& n : names_in(staging_))
      if (is_folder_at(old_fd.fd, n))
        throw std::runtime_error(
            fmt::format("cannot put {} into {}: a folder of that name is there", n, named_));
    // The earlier folder's other entries carried across: files linked (present in both until the
    // swap), folders moved (absent from the earlier folder for the instant before the swap).
    std::vector<std::string> moved, folders;
    bool stuck = false;  // an entry of the user's that could be neither linked nor moved
    for (const std::string& n : names_in(dir_)) {
      if (exists_at(new_fd.fd, n)) {
        // The new set's file of that name wins: the earlier one goes with the earlier folder.
        struct stat was;
        if (!is_folder_at(old_fd.fd, n) && ::fstatat(old_fd.fd, n.c_str(), &was, AT_SYMLINK_NOFOLLOW) == 0)
          superseded.emplace_back(n, was.st_ino);
        continue;
      }
      if (is_folder_at(old_fd.fd, n)) {
        folders.push_back(n);  // moved once every file is linked: absent only for that instant
        continue;
      }
      if (in_earlier_set(n)) {
        out.dropped.push_back(n);
        continue;
      }
      if (is_dead_temporary(n)) continue;
      if (::linkat(old_fd.fd, n.c_str(), new_fd.fd, n.c_str(), 0) == 0) continue;
      // A file that cannot be linked (another user's, where links are protected): moved.
      if (::renameat(old_fd.fd, n.c_str(), new_fd.fd, n.c_str()) == 0) moved.push_back(n);
      else stuck = true;
    }
    for (const std::string& n : folders) {
      if (::renameat(old_fd.fd, n.c_str(), new_fd.fd, n.c_str()) == 0) moved.push_back(n);
      else stuck = true;
    }
    // The folder keeps what the user set on it: its permissions, and its owner where this process may.
    ::fchmod(new_fd.fd, st.st_mode & 07777);
    if (::fchown(new_fd.fd, st.st_uid, st.st_gid) != 0) {
      // not the owner's to give: the new folder is this user's
    }
    const auto put_back = [&] {
      for (const std::string& n : moved) ::renameat(new_fd.fd, n.c_str(), old_fd.fd, n.c_str());
    };
    // Checked again at the last moment: the entries were carried from the folder read.
    if (required_ && (is_another(old_fd.fd) || !(folder_identity(dir_, required_file_) == *required_))) {
      put_back();
      throw replaced_meanwhile(dir_);
    }
    if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, dir_.c_str(), RENAME_EXCHANGE) == 0) {
      old_path = staging_;
    } else if (errno == EINVAL || errno == ENOSYS || errno == EOPNOTSUPP) {
      // A file system without the exchange: two renames, the folder absent (never mixed) between.
      old_path = staging_ + "-old";
      if (::rename(dir_.c_str(), old_path.c_str()) != 0) {
        const std::string reason = why();
        put_back();
        throw std::runtime_error(fmt::format("cannot replace {}: {}", dir_, reason));
      }
      if (::rename(staging_.c_str(), dir_.c_str()) != 0) {
        const std::string reason = why();
        ::rename(old_path.c_str(), dir_.c_str());
        put_back();
        throw std::runtime_error(fmt::format("cannot replace {}: {}", dir_, reason));
      }
    } else {
      const std::string reason = why();
      put_back();
      throw std::runtime_error(fmt::format("cannot replace {}: {}", dir_, reason));
    }
    // A signal from here on finishes the removal, unless something of the user's is left there.
    if (stuck) unregister_run_path(staging_id_);
    else rename_run_path(staging_id_, old_path);
  }
  committed_ = true;
  for (std::uint64_t id : created_ids_) unregister_run_path(id);
  lock.unlock();
  // The earlier files stay open while their names go: removing the name of an open file is
  // quick, and the file's blocks are freed when it is closed, once no name of the run is left (a
  // 10-plant stand's 0.3 GB of meshes took 45 ms to unlink by name, a SIGKILL then leaving the
  // earlier folder half removed under the staging name).
  struct Held {
    std::vector<int> fds;
    ~Held() {
      for (int fd : fds)
        if (fd >= 0) ::close(fd);
    }
  };
  {
    Held held;
    if (!old_path.empty()) {
      // Only files the new folder has a file of the same name for (linked, or written again by the
      // new set), the earlier set and dead runs' temporaries go.
      Fd old_fd(old_path), new_fd(dir_);
      const std::vector<std::string> entries = names_in(old_path);
      held.fds.reserve(entries.size());  // no allocation between an open and its keeping
      const bool hold = frees_on_close(old_fd.fd);
      for (const std::string& n : entries) {
        if (is_folder_at(old_fd.fd, n)) continue;
        const bool linked = same_file_at(old_fd.fd, new_fd.fd, n);  // the user's file, in both
        if (in_earlier_set(n) || is_dead_temporary(n) || linked || still_superseded(old_fd.fd, n)) {
          if (hold && !linked)
            held.fds.push_back(::openat(old_fd.fd, n.c_str(), O_PATH | O_NOFOLLOW | O_CLOEXEC));
          ::unlinkat(old_fd.fd, n.c_str(), 0);
        }
      }
      if (::rmdir(old_path.c_str()) != 0)
        out.notes.push_back(
            fmt::format("kept the earlier folder as {}: it holds {} that could not be moved into {}",
                        old_path, fmt::join(names_in(old_path), ", "), dir_));
    }
    unregister_run_path(staging_id_);
    // The swap and the removal on disk, then (held's end) the earlier files let go.
    sync_folder(parent_);
  }
  return out;
}

}  // namespace canopy
