#pragma once
/// The stand's files written by every rank into one set of files with MPI-IO: each rank writes
/// the chunks of the plants it owns at their global offsets (prefix sums of every rank's chunk
/// sizes, in global plant order), rank 0 the fixed text; no rank ever holds the whole file.
/// Files are written into rank 0's staging folder and swapped in as one set once every rank has
/// succeeded (geometry/staged_folder.hpp), as one process does.
#include "geometry/chunked_output.hpp"
#include "geometry/staged_folder.hpp"

#include <memory>
#include <string>
#include <vector>

namespace canopy::mpi {

/// PlantScan over every rank: `ids` are the global ids of this rank's written plants, in order.
class RankScan final : public PlantScan {
 public:
  RankScan(std::vector<std::int64_t> ids, std::uint64_t plants_total)
      : ids_(std::move(ids)), total_(plants_total) {}
  void exclusive(std::vector<std::uint64_t>& values, int k,
                 std::vector<std::uint64_t>& totals) const override;

 private:
  std::vector<std::int64_t> ids_;
  std::uint64_t total_;
};

class SharedFile final : public ChunkWriter {
 public:
  SharedFile(const std::string& path, const std::vector<std::int64_t>& ids, std::uint64_t plants_total);
  ~SharedFile() override;
  void fixed(std::string_view text) override;
  void plants(std::size_t n, std::size_t batch,
              const std::function<void(std::size_t, std::string&)>& make) override;
  std::uint64_t offset() const override { return offset_; }
  void patch(std::uint64_t at, std::string_view bytes) override;
  /// Text that rank 0 alone has (the report): written by rank 0 at the current offset.
  void root_text(std::string_view text);
  /// Collective: closes the file (every rank's writes are then in it).
  void close();
  const std::string& path() const { return path_; }

 private:
  void write_at(std::uint64_t at, const char* data, std::size_t n);
  std::string path_;
  const std::vector<std::int64_t>& ids_;
  std::uint64_t plants_total_;
  std::uint64_t offset_ = 0;
  void* handle_ = nullptr;  // MPI_File
};

/// The files of one tiled run in `dir`: collective. Rank 0 makes the staging folder (replacing
/// `replaces` of the earlier folder where it holds `marker`, see StagedFolder) and tells the
/// others where it is.
class SharedOutputSet {
 public:
  SharedOutputSet(const std::string& dir, std::vector<std::string> replaces, std::string marker,
                  std::vector<std::int64_t> ids, std::uint64_t plants_total);
  ~SharedOutputSet();  // rank 0 removes the staging folder unless committed
  SharedFile& open(const std::string& name);
  /// Collective: closes every file, checks that every rank wrote without error, then rank 0
  /// swaps the set in; every rank throws the first failure.
  void commit_all(const std::string& local_error = {});
  const std::vector<std::int64_t>& ids() const { return ids_; }
  /// Removes the staging folder's files and the folder (any rank; before an abort).
  void remove_temporaries() const;
  /// Rank 0: the folder and what its swap did (for print_folder_changes); null elsewhere.
  const StagedFolder* folder() const { return folder_.get(); }
  const StagedFolder::Committed& committed() const { return committed_set_; }

 private:
  std::unique_ptr<StagedFolder> folder_;  // rank 0
  std::string staging_;                   // every rank
  std::vector<std::int64_t> ids_;
  std::uint64_t plants_total_;
  std::vector<std::pair<std::string, std::unique_ptr<SharedFile>>> files_;
  StagedFolder::Committed committed_set_;
  bool committed_ = false;
};

}  // namespace canopy::mpi
