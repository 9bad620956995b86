#pragma once
/// Files written whole or not at all (docs/design.md "Export files"). A single file (a sweep's tables, a
/// CSV named with --csv) is written under a temporary name beside its final one, synced and
/// renamed into place. The files of a stand are an OutputSet: written into a staging folder and
/// swapped in together (geometry/staged_folder.hpp). Temporary names carry the writing process
/// (geometry/run_files.hpp): a signal's clean-up removes this run's, a later run a dead run's.
#include "geometry/staged_folder.hpp"

#include <cstdint>

#include <cstdio>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace canopy {

/// What writing a file cost (tools report export formatting apart from writing).
struct WriteTimes {
  std::uint64_t bytes = 0;
  double busy_s = 0;    // in write calls and the final flush, on whichever thread made them
  double waited_s = 0;  // of which the exporting thread waited (its own writes, or for a writer thread)
  WriteTimes& operator+=(const WriteTimes& o) {
    bytes += o.bytes, busy_s += o.busy_s, waited_s += o.waited_s;
    return *this;
  }
};

class AtomicFile {
 public:
  /// Written as "PATH.tmp-PID-START" (what dead runs left under that name removed first).
  explicit AtomicFile(std::string path);
  /// A file written in place, with no temporary name (/dev/null in benchmarks, a file of a
  /// staging folder).
  struct Direct {};
  AtomicFile(std::string path, Direct);
  /// An unnamed file already open on `fd` (StagedFolder::unnamed_file), owned from here on;
  /// `path` names it in messages.
  struct Unnamed {};
  AtomicFile(int fd, std::string path, Unnamed);
  ~AtomicFile();  // removes the temporary file unless committed
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::FILE* get() const { return f_; }
  void write(const void* data, std::size_t n);
  void write(std::string_view s) { write(s.data(), s.size()); }
  /// A write made by a writer thread while the exporting thread goes on (write_ordered): counted
  /// as busy, not as waited.
  void write_behind(std::string_view s);
  /// The exporting thread waited `seconds` for a writer thread.
  void add_waited(double seconds) { times_.waited_s += seconds; }
  const WriteTimes& times() const { return times_; }
  /// Flushes and syncs the open file; throws on a write error.
  void sync();
  /// Flushes and closes; throws on a write error. The file is not yet in place.
  void close();
  bool unnamed() const { return unnamed_; }
  /// Syncs the closed temporary file, renames it to its final name and syncs the folder.
  void commit();
  const std::string& path() const { return path_; }

 private:
  std::string path_, tmp_;
  std::FILE* f_ = nullptr;
  std::uint64_t registered_ = 0;
  bool committed_ = false;
  bool direct_ = false;
  bool unnamed_ = false;
  WriteTimes times_;
  void write_raw(const void* data, std::size_t n);
};

/// The files of one stand: each written in full as an unnamed file (or into the staging folder),
/// then linked into the staging folder and swapped in together, replacing the folder's earlier
/// files named in `replaces` (see StagedFolder).
class OutputSet {
 public:
  explicit OutputSet(const std::string& dir, std::vector<std::string> replaces = {}, std::string marker = {});
  AtomicFile& open(const std::string& name);
  /// Syncs every file and links the unnamed ones into the staging folder, closes them (throwing
  /// on a write error), then StagedFolder::commit.
  StagedFolder::Committed commit_all();
  /// The final folder.
  const std::string& dir() const { return folder_.dir(); }
  const StagedFolder& folder() const { return folder_; }
  /// See StagedFolder::require_folder.
  void require_folder(FolderIdentity read, std::string file) { folder_.require_folder(read, std::move(file)); }
  /// The files' write times and bytes, summed (those already committed included).
  WriteTimes times() const;

 private:
  StagedFolder folder_;
  std::vector<std::unique_ptr<AtomicFile>> files_;
  std::vector<std::string> names_;  // beside files_
  WriteTimes closed_;
};

/// Checks that a run can later write its folder `dir`, changing nothing (check_output_dir); the
/// folder itself is made only when the run's files are complete, so a failed run leaves none.
inline void prepare_output_dir(const std::string& dir) { check_output_dir(dir); }

}  // namespace canopy
