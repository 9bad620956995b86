// A staged folder committed in place: the output folder is the working folder or a mount point,
// so it must stay the folder it is and cannot be swapped for the staging folder. The staging
// folder is made inside it; once every file is complete and synced, a list of the earlier set's
// files the new set drops is written there and synced, then the files are moved in one by one
// and the dropped ones removed. Readers that open the folder's files together
// (open_in_one_set) see the folder change and open them again; a run killed while moving leaves
// the list, and the next run into the folder finishes the move before anything else.
#include "geometry/folder_ops.hpp"
#include "geometry/run_files.hpp"
#include "geometry/staged_folder.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace canopy {
using namespace folder_ops;
namespace {

std::vector<std::string> read_list(const std::string& path) {
  std::vector<std::string> out;
  if (std::FILE* f = std::fopen(path.c_str(), "rb")) {
    std::string line;
    for (int c; (c = std::fgetc(f)) != EOF;) {
      if (c != '\n') line += static_cast<char>(c);
      else if (!line.empty()) out.push_back(line), line.clear();
    }
    std::fclose(f);
  }
  return out;
}

/// Moves every file of `staging` but its list into `dir`, removes `drop` from `dir`, then the
/// list and the staging folder; false (with errno) where a move fails.
bool finish(const std::string& dir, const std::string& staging, const std::vector<std::string>& drop) {
  Fd from(staging), to(dir);
  if (from.fd < 0 || to.fd < 0) return false;
  for (const std::string& n : names_in(staging))
    if (n != kCommitList && ::renameat(from.fd, n.c_str(), to.fd, n.c_str()) != 0) return false;
  for (const std::string& n : drop) ::unlinkat(to.fd, n.c_str(), 0);  // gone already: no matter
  ::fsync(to.fd);
  ::unlinkat(from.fd, kCommitList, 0);
  return ::rmdir(staging.c_str()) == 0;
}

}  // namespace

StagedFolder::Committed StagedFolder::commit_in_place() {
  Committed out;
  Fd to(dir_), from(staging_);
  if (to.fd < 0 || from.fd < 0) throw std::runtime_error(fmt::format("cannot open {}: {}", dir_, why()));
  // One run at a time moves its files into the folder: two runs at once, each reading what the
  // folder held and moving its own files in, left files of both stands (3 to 12 of 40 rounds of
  // three runs into `-o .`). The turn is taken before the registry's lock, so that a signal can
  // end the run while it waits; the next run reads the folder once the first is done.
  std::string waited;
  const FolderTurn turn(to.fd, named_, waited);
  if (!waited.empty()) out.notes.push_back(waited);
  auto lock = lock_run_paths();  // a signal waits until every file is in place
  if (required_ && !(folder_identity(dir_, required_file_) == *required_)) throw replaced_meanwhile(dir_);
  // What would stop a file going in, found before any does (the run then fails with the folder as
  // it was): a folder of its name.
  for (const std::string& n : names_in(staging_))
    if (is_folder_at(to.fd, n))
      throw std::runtime_error(
          fmt::format("cannot put {} into {}: a folder of that name is there", n, named_));
  // A folder without the marker holds no earlier set: files of those names are the user's.
  if (marker_.empty() || exists_at(to.fd, marker_))
    for (const std::string& n : replaces_)
      if (!exists_at(from.fd, n) && exists_at(to.fd, n) && !is_folder_at(to.fd, n)) out.dropped.push_back(n);
  {
    const std::string list = staging_ + "/" + kCommitList;
    std::string text;
    for (const std::string& n : out.dropped) text += n + "\n";
    std::FILE* f = std::fopen(list.c_str(), "wb");
    const bool ok = f && std::fwrite(text.data(), 1, text.size(), f) == text.size() && std::fflush(f) == 0 &&
                    ::fsync(fileno(f)) == 0;
    if (f) std::fclose(f);
    if (!ok) throw std::runtime_error(fmt::format("cannot write {}: {}", list, why()));
    ::fsync(from.fd);
  }
  if (!finish(dir_, staging_, out.dropped)) {
    // Some files are in and the earlier ones they replaced are gone: the staging folder and its
    // list stay for the next run into the folder to finish (a signal no longer removes them).
    const std::string reason = why();
    committed_ = true;
    unregister_run_path(staging_id_);
    throw std::runtime_error(fmt::format(
        "cannot move the files of {} into {}: {}; the folder holds files of two stands until the next run "
        "into {} finishes the move",
        staging_, dir_, reason, named_));
  }
  committed_ = true;
  unregister_run_path(staging_id_);
  staging_id_ = 0;
  for (std::uint64_t id : created_ids_) unregister_run_path(id);
  return out;
}

void StagedFolder::finish_in_place_leftovers() {
  for (const InPlaceStaging& staging : in_place_stagings(dir_)) {
    if (!tag_is_dead(staging.tag)) continue;
    const std::string& e = staging.name;
    const std::string path = dir_ + "/" + e;
    Fd at(path);
    if (at.fd >= 0 && exists_at(at.fd, kCommitList)) {
      // Killed while moving its files in: finished now, so the folder holds one set again (in
      // its turn, as a commit moves files in).
      Fd folder(dir_);
      std::string waited;
      const FolderTurn turn(folder.fd, named_, waited);
      if (!waited.empty()) leftover_notes_.push_back(waited);
      if (!exists_at(at.fd, kCommitList)) continue;  // another run finished it meanwhile
      if (finish(dir_, path, read_list(path + "/" + kCommitList))) leftovers_.push_back(e + " (its files moved in)");
      else
        leftover_notes_.push_back(
            fmt::format("kept {}, left by a run that ended while moving its files into {}: {}", path, dir_, why()));
    } else if (remove_flat_folder(path)) {
      leftovers_.push_back(e);  // ended before its files were complete
    }
  }
}

}  // namespace canopy
