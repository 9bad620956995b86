#include "geometry/run_files.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sys/types.h>
#include <unistd.h>

namespace canopy {
namespace {

namespace fs = std::filesystem;

/// What /proc/PID/stat says of a process: its state (field 3; 0 when unread) and its start time
/// in clock ticks since boot (field 22; 0 when unread).
struct ProcStat {
  char state = 0;
  std::uint64_t start = 0;
};

ProcStat proc_stat(const std::string& pid) {
  ProcStat out;
  std::ifstream in("/proc/" + pid + "/stat");
  std::string line;
  if (!std::getline(in, line)) return out;
  // The command name (field 2) is in parentheses and may hold spaces and parentheses itself.
  const std::size_t close = line.rfind(')');
  if (close == std::string::npos) return out;
  std::size_t at = close + 1;
  for (int field = 3; field <= 22; ++field) {
    while (at < line.size() && line[at] == ' ') ++at;
    const std::size_t end = std::min(line.find(' ', at), line.size());
    if (field == 3 && at < end) out.state = line[at];
    if (field == 22) std::from_chars(line.data() + at, line.data() + end, out.start);
    at = end;
  }
  return out;
}

struct Entry {
  std::uint64_t id;
  std::string path;
  RunPath kind;
};

struct Registry {
  std::recursive_mutex mutex;
  std::vector<Entry> entries;
  std::uint64_t next = 1;
};

Registry& registry() {
  static Registry* r = new Registry;  // never destroyed: a signal may come while statics are torn down
  return *r;
}

bool parse_number(std::string_view s, std::uint64_t& v) {
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  return !s.empty() && r.ec == std::errc() && r.ptr == s.data() + s.size();
}

}  // namespace

const std::string& process_tag() {
  static const std::string tag = [] {
    const std::string pid = std::to_string(::getpid());
    return pid + "-" + std::to_string(proc_stat("self").start);
  }();
  return tag;
}

bool tag_is_dead(std::string_view tag) {
  const std::size_t dash = tag.find('-');
  std::uint64_t pid = 0, start = 0;
  if (!parse_number(tag.substr(0, dash), pid) || pid == 0 || pid > 0x3fffffff) return false;
  if (dash != std::string_view::npos && !parse_number(tag.substr(dash + 1), start)) return false;
  if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) return true;
  // The pid is in use: by the same process unless it started at another time, or has ended and
  // waits to be reaped (a zombie: its parent was killed with it, as `timeout -s KILL` does).
  const ProcStat now = proc_stat(std::to_string(pid));
  if (now.state == 'Z' || now.state == 'X') return true;
  return start != 0 && now.start != 0 && now.start != start;
}

std::uint64_t register_run_path(std::string path, RunPath kind) {
  Registry& r = registry();
  std::lock_guard lock(r.mutex);
  r.entries.push_back({r.next, std::move(path), kind});
  return r.next++;
}

void unregister_run_path(std::uint64_t id) {
  if (id == 0) return;
  Registry& r = registry();
  std::lock_guard lock(r.mutex);
  std::erase_if(r.entries, [id](const Entry& e) { return e.id == id; });
}

void rename_run_path(std::uint64_t id, std::string path) {
  Registry& r = registry();
  std::lock_guard lock(r.mutex);
  for (Entry& e : r.entries)
    if (e.id == id) e.path = std::move(path);
}

std::unique_lock<std::recursive_mutex> lock_run_paths() { return std::unique_lock(registry().mutex); }

bool remove_flat_folder(const std::string& path) {
  std::error_code ec;
  for (fs::directory_iterator it(path, ec), end; !ec && it != end; it.increment(ec))
    if (!it->is_directory(ec) || it->is_symlink(ec)) fs::remove(it->path(), ec);
  return ::rmdir(path.c_str()) == 0 || errno == ENOENT;
}

std::vector<std::string> remove_run_paths() {
  Registry& r = registry();
  std::lock_guard lock(r.mutex);
  std::vector<std::string> removed;
  // Out of memory (this runs from the terminate handler too) loses a name from the list, never a
  // removal.
  const auto note = [&](const std::string& path) {
    try {
      removed.push_back(path);
    } catch (...) {
    }
  };
  for (const Entry& e : r.entries)
    if (e.kind == RunPath::file && ::unlink(e.path.c_str()) == 0) note(e.path);
  for (const Entry& e : r.entries) {
    std::error_code ec;
    if (e.kind == RunPath::staging && fs::exists(fs::symlink_status(e.path, ec)) && remove_flat_folder(e.path))
      note(e.path);
  }
  for (auto it = r.entries.rbegin(); it != r.entries.rend(); ++it)
    if (it->kind == RunPath::created_folder && ::rmdir(it->path.c_str()) == 0) note(it->path);
  r.entries.clear();
  return removed;
}

}  // namespace canopy
