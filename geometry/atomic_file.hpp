#pragma once
/// Files written under a temporary name in their final folder and renamed into place only when
/// every file of a run is complete, so a failed run leaves no half file (DESIGN.md "Exports").
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
  explicit AtomicFile(std::string path);
  /// A file written in place, with no temporary name (for /dev/null in benchmarks).
  struct Direct {};
  AtomicFile(std::string path, Direct);
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
  /// Flushes and closes; throws on a write error. The file is not yet in place.
  void close();
  /// Renames the closed temporary file to its final name.
  void commit();
  const std::string& path() const { return path_; }

 private:
  std::string path_, tmp_;
  std::FILE* f_ = nullptr;
  bool committed_ = false;
  bool direct_ = false;
  WriteTimes times_;
  void write_raw(const void* data, std::size_t n);
};

/// The files of one run: each written in full, then all renamed into place together.
class OutputSet {
 public:
  explicit OutputSet(std::string dir);
  AtomicFile& open(const std::string& name);
  void commit_all();
  const std::string& dir() const { return dir_; }
  /// The files' write times and bytes, summed.
  WriteTimes times() const;

 private:
  std::string dir_;
  std::vector<std::unique_ptr<AtomicFile>> files_;
};

/// Creates `dir` if needed and checks that a file can be written there; throws with the reason.
void prepare_output_dir(const std::string& dir);

}  // namespace canopy
