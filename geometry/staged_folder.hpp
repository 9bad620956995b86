#pragma once
/// A folder whose set of files is replaced as one unit (docs/design.md "Export files": a run replaces the
/// folder's stand as one unit; docs/design.md "Output folders and failures"). The files are
/// written as unnamed files (O_TMPFILE) of the file system the folder is on, which vanish with
/// the process however it ends; once all are complete they are synced and linked into a staging
/// folder beside it, ".NAME.canopy-PID-START-K" (geometry/run_files.hpp), made only then, and
/// swapped in with one renameat2(RENAME_EXCHANGE) (one rename when the folder is new); the
/// earlier folder, now at the staging name, is then removed. Where unnamed files cannot be made,
/// the staging folder is made at the first file and the files are written into it by name. A
/// reader that opens the folder sees the earlier set or the new one, never a mix.
///
/// What a replaced folder keeps: every entry of the earlier folder except the files named in
/// `replaces` (the earlier set, dropped whether the new set has them or not), the files the new
/// set writes again (the new ones replace them) and dead runs' temporary files. Other files (the
/// user's, a sweep's tables) are hard-linked into the new folder before the swap, so they are
/// never absent; other folders are moved into it just before the swap. Nothing is ever removed recursively: a
/// folder that cannot be carried across keeps the earlier folder in place under its staging name, and
/// commit() says so.
///
/// The working folder and mount points cannot be swapped: they are committed in place, the
/// staging folder inside them and the files moved in one by one (geometry/staged_in_place.cpp).
#include <cstdint>
#include <fstream>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace canopy {

/// The folder a staged run replaces: `dir` made absolute and normal, a symbolic link to a folder
/// followed (the link stays, its target is replaced). Throws std::runtime_error for "/".
std::string output_folder(const std::string& dir);

/// Checks, leaving nothing behind, that a StagedFolder can later replace `dir`: an existing `dir`
/// is a folder (the working folder and mount points are written in place, a folder made inside
/// them: geometry/staged_in_place.cpp); a folder can be made beside it, or in its nearest
/// existing ancestor when it is new. Throws std::runtime_error "cannot create the output folder
/// DIR: why".
void check_output_dir(const std::string& dir);

/// Which folder a path names now (device and inode; zeros where there is none), and which file
/// `file` is in it (its inode; 0 where there is none): a run that writes the folder in place
/// keeps the folder and replaces its files.
struct FolderIdentity {
  std::uint64_t dev = 0, ino = 0, file_ino = 0;
  bool operator==(const FolderIdentity&) const = default;
};
FolderIdentity folder_identity(const std::string& dir, const std::string& file = {});

class StagedFolder {
 public:
  /// Removes what dead runs left beside `dir` (their staging folders), putting back into `dir`
  /// anything of the user's that such a run had carried across. The folders missing above `dir`
  /// and the staging folder are made later, when the first file is linked in or named.
  /// `replaces`: see above; with a `marker`, only an earlier folder that holds a file of that
  /// name holds an earlier set (a stand folder holds organs.csv): elsewhere files of those names
  /// are the user's, kept unless the new set writes them again.
  StagedFolder(const std::string& dir, std::vector<std::string> replaces, std::string marker = {});
  /// Not committed: removes the staging folder and the folders made for it.
  ~StagedFolder();
  StagedFolder(const StagedFolder&) = delete;
  StagedFolder& operator=(const StagedFolder&) = delete;

  const std::string& dir() const { return dir_; }
  /// Makes the staging folder (and the folders missing above `dir`) now, for writers that name
  /// their files themselves (MPI ranks writing one shared file).
  void make();
  /// The staging folder's name (the folder exists once made, a file linked in or named).
  const std::string& staging() const { return staging_; }
  /// A file of the staging folder (made now, with the folders missing above it).
  std::string path(const std::string& name);
  /// A new unnamed file, open for writing, on the file system of the folder, or -1 where this
  /// file system or machine cannot make one.
  int unnamed_file() const;
  /// Whether unnamed_file() can make one here (one made and dropped).
  bool unnamed_file_possible() const;
  /// Links unnamed file `fd` into the staging folder (made now) as `name`.
  void link_in(int fd, const std::string& name);
  /// The files were made from the folder `read`, read with its `file` (canopy light DIR reads a
  /// stand and adds its light): commit() refuses, leaving `dir` as it is, where `dir` is by then
  /// another folder or none, or its `file` another file (another run replaced the folder or its
  /// stand meanwhile; the light would join a stand it was not made for).
  void require_folder(FolderIdentity read, std::string file) {
    required_ = read;
    required_file_ = std::move(file);
  }

  struct Committed {
    std::vector<std::string> dropped;  // names in `replaces` the earlier folder had and the new set has not
    std::vector<std::string> notes;    // what was not done as planned (an earlier folder kept), a line each
  };
  /// Syncs every file of the staging folder and the folder, carries the earlier folder's other
  /// entries across, swaps, syncs the parent, removes the earlier folder. Throws, with `dir` as it
  /// was, when the swap cannot be made.
  Committed commit();

  /// Names of dead runs' leftovers removed by the constructor, and notes on those it kept.
  const std::vector<std::string>& leftovers_removed() const { return leftovers_; }
  const std::vector<std::string>& leftover_notes() const { return leftover_notes_; }

 private:
  void open(const std::string& dir);
  void remove_leftovers();
  /// In place (geometry/staged_in_place.cpp): the files moved into the folder one by one, and what
  /// a run killed while doing so left finished by the next.
  Committed commit_in_place();
  void finish_in_place_leftovers();
  std::string dir_, named_, base_, parent_, name_, staging_;
  bool made_ = false;
  bool in_place_ = false;  // the output folder stays the folder it is (see staging_place)
  std::vector<std::string> replaces_;
  std::string marker_;
  std::uint64_t staging_id_ = 0;
  std::vector<std::uint64_t> created_ids_;
  std::vector<std::string> created_;
  std::vector<std::string> leftovers_, leftover_notes_;
  std::vector<std::string> linked_;  // files linked in by link_in, synced before they had a name
  bool committed_ = false;
  std::optional<FolderIdentity> required_;
  std::string required_file_;
};

/// Opens `files[i]` on `paths[i]` (files of folder `dir`) so that all come from one set: the
/// folder's identity and its files' are read before and after they are opened, and they are
/// opened again when a run swapped the folder or replaced a file in between; while a run moves
/// its files into the folder in place, opening waits for it (up to about two seconds). Once
/// open, a file reads whole whatever replaces it.
void open_in_one_set(const std::string& dir, const std::vector<std::ifstream*>& files,
                     const std::vector<std::string>& paths);
/// The same rule for any way of opening: `open_all` (which replaces what it opened before, the
/// files `paths`) is called again until neither the folder nor those files changed while it ran.
void open_in_one_set(const std::string& dir, const std::vector<std::string>& paths,
                     const std::function<void()>& open_all);

/// Whether `name` is a temporary file of a canopy run that has ended ("X.tmp-PID[-START]" with
/// that process gone) or a temporary name of an earlier canopy version: safe to remove.
bool is_dead_temporary(const std::string& name);

}  // namespace canopy
