#pragma once
/// Exports written as fixed text plus one chunk per plant, in global plant order, so that one
/// process or several (each holding a tile of the stand) write the same bytes. A writer sees an
/// ExportScope (which plants it writes, how their local ids map to the whole stand's, and the
/// prefix sums it needs over the plants written by every process) and a ChunkWriter (where the
/// text goes). One process: ExportScope::whole + ChunkFile; tiles over MPI: distributed/.
#include "geometry/atomic_file.hpp"
#include "geometry/stand.hpp"

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace canopy {

/// Exclusive prefix sums over the plants written by all processes, in global plant order.
class PlantScan {
 public:
  virtual ~PlantScan() = default;
  /// `values` holds k numbers per written plant of this process; each is replaced by the sum of
  /// the same number over the plants (of every process) before it; `totals` gets the k sums.
  virtual void exclusive(std::vector<std::uint64_t>& values, int k,
                         std::vector<std::uint64_t>& totals) const = 0;
};

/// In place: each of the k columns of `values` (rows of k) replaced by the sum of the rows
/// before it; `totals` gets the column sums.
void exclusive_sums(std::vector<std::uint64_t>& values, int k, std::vector<std::uint64_t>& totals);

/// Which plants of a (possibly partial) stand a writer writes, and their global numbering.
struct ExportScope {
  const Stand& stand;
  std::vector<std::uint32_t> plants;      // local plants written, ascending in global id
  std::vector<std::int64_t> plant_id;     // per local plant: its global id
  std::vector<std::int64_t> organ_shift;  // per local plant: global organ id - local organ id
  std::vector<std::int64_t> leaf_shift;   // per local plant: global leaf id - local leaf id
  std::uint64_t plants_total = 0, organs_total = 0;
  const PlantScan* scan = nullptr;  // null: this process writes every plant

  /// The whole stand written by this process alone.
  static ExportScope whole(const Stand& stand);

  std::int64_t organ(std::int64_t local) const {
    return local < 0 ? -1
                     : local + organ_shift[static_cast<std::size_t>(
                                   stand.organs[static_cast<std::size_t>(local)].plant)];
  }
  std::int64_t leaf_of(std::size_t local_organ) const {
    const OrganRecord& r = stand.organs[local_organ];
    return r.leaf < 0 ? -1 : r.leaf + leaf_shift[static_cast<std::size_t>(r.plant)];
  }
  std::int64_t plant(std::size_t local) const { return plant_id[local]; }
  /// Exclusive prefix sums (k per written plant, see PlantScan) and their totals.
  void exclusive(std::vector<std::uint64_t>& values, int k, std::vector<std::uint64_t>& totals) const;
};

/// Where an export's bytes go: fixed text (the same on every process, written once) and sections
/// of one chunk per written plant, laid out in global plant order.
class ChunkWriter {
 public:
  virtual ~ChunkWriter() = default;
  virtual void fixed(std::string_view text) = 0;
  /// One section: `make(i, out)` appends the chunk of the i-th written plant (called on all threads,
  /// any order; `batch` plants per task).
  virtual void plants(std::size_t n, std::size_t batch,
                      const std::function<void(std::size_t, std::string&)>& make) = 0;
  /// Global offset of the next byte.
  virtual std::uint64_t offset() const = 0;
  /// Overwrites bytes written earlier at global offset `at` (lengths known only at the end).
  virtual void patch(std::uint64_t at, std::string_view bytes) = 0;
};

/// A ChunkWriter into one AtomicFile of this process.
class ChunkFile final : public ChunkWriter {
 public:
  explicit ChunkFile(AtomicFile& out) : out_(out) {}
  void fixed(std::string_view text) override;
  void plants(std::size_t n, std::size_t batch,
              const std::function<void(std::size_t, std::string&)>& make) override;
  std::uint64_t offset() const override { return offset_; }
  void patch(std::uint64_t at, std::string_view bytes) override;

 private:
  AtomicFile& out_;
  std::uint64_t offset_ = 0;
};

}  // namespace canopy
