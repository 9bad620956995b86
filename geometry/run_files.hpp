#pragma once
/// What a run has on disk that is not yet in place (a file under a temporary name, a stand's
/// staging folder, the old stand folder being removed, folders created for the output), kept in
/// one registry so that a run stopped by SIGINT or SIGTERM removes it (tools/signals.hpp), and
/// named after the process that made it, so that a later run removes what a dead one left
/// (SIGKILL, power loss). docs/design.md "Export files"; docs/design.md "Output folders and failures".
#include <cstdint>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

namespace canopy {

/// This process in temporary names: "<pid>-<start>", the start being the process's start time
/// in clock ticks since boot (/proc/self/stat; 0 where it cannot be read), so that a pid the
/// system has given to another process since is not taken for the process that named a file.
const std::string& process_tag();

/// Whether the process a tag names ("<pid>-<start>", or "<pid>" alone as older canopy versions
/// wrote) has ended: no such pid, or a pid that now belongs to a process started at another time.
/// A tag that is not one, or a process it cannot tell about, counts as alive: nothing is removed
/// on a guess.
bool tag_is_dead(std::string_view tag);

/// What a registered path is and how it is removed.
enum class RunPath : std::uint8_t {
  file,            // unlinked
  staging,         // a folder of files this run wrote: its files unlinked, then the folder
  created_folder,  // a folder made for the output: removed only when empty
};

/// Registers `path`; returns an id for unregister_run_path. Thread safe.
std::uint64_t register_run_path(std::string path, RunPath kind);
/// The entry is in place or removed: forget it. Id 0 is ignored.
void unregister_run_path(std::uint64_t id);
/// Points entry `id` at another path (a folder renamed while registered).
void rename_run_path(std::uint64_t id, std::string path);

/// Held while a run moves its files into place, so that a signal's clean-up sees the folder
/// either before the swap or after it (recursive: the holder may register and unregister).
std::unique_lock<std::recursive_mutex> lock_run_paths();

/// Removes every registered path (files, then staging folders' files and the folders, then
/// created folders that are empty, newest first), forgets them and returns the paths removed.
/// The signal thread holds lock_run_paths() across it and keeps it: the process ends after.
std::vector<std::string> remove_run_paths();

/// Removes the entries of folder `path` that are not folders, then the folder itself when that
/// leaves it empty; never descends into a folder (what it holds may be the user's). Returns
/// whether the folder is gone.
bool remove_flat_folder(const std::string& path);

}  // namespace canopy
