#pragma once
/// Files written under a temporary name in their final folder and renamed into place only when
/// every file of a run is complete, so a failed run leaves no half file (DESIGN.md "Exports").
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace canopy {

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
};

/// The files of one run: each written in full, then all renamed into place together.
class OutputSet {
 public:
  explicit OutputSet(std::string dir);
  AtomicFile& open(const std::string& name);
  void commit_all();
  const std::string& dir() const { return dir_; }

 private:
  std::string dir_;
  std::vector<std::unique_ptr<AtomicFile>> files_;
};

/// Creates `dir` if needed and checks that a file can be written there; throws with the reason.
void prepare_output_dir(const std::string& dir);

}  // namespace canopy
