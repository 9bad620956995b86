#pragma once
/// Whether a stand's contact lists fit in memory, said before they are made (docs/design.md
/// "Output folders and failures"). The stand's own arrays are checked before growing
/// (lsystem/grow.hpp); what detection and resolution add grows with the plant pairs whose bounds
/// meet and with the contacts found, which plants standing on or near one spot make explode (the
/// pairs as the square of the plants): 200 tomato plants on one spot meet in 19,900 pairs and
/// make 2.1 million exact contacts.
///
/// Three bounds, each a clear refusal instead of an out-of-memory kill:
/// - before detection's lists, the plant pairs whose bounds meet, counted (no list made):
///   kBytesPerPlantPair each (the plant level's work, pair and contact records);
/// - during CPU detection, the leaf and organ lists: they stop at memory / kBytesPerContact;
/// - before resolution, kResolutionBytesPerContact per contact it starts from (measured on the
///   development machine: 12-14 KB per contact, 300 plants in rows and 50 on one spot alike).
#include <cstddef>
#include <cstdint>

namespace canopy {

inline constexpr double kBytesPerPlantPair = 64;
inline constexpr double kBytesPerContact =
    96;  // a 24-byte record in a thread's list, the merged list and the sorted answer, grown by doubling
inline constexpr double kResolutionBytesPerContact = 16 << 10;

/// The memory a check allows: `limit` when set, else what the machine has available (0: unknown,
/// no check).
std::size_t memory_budget(std::size_t limit);

/// The most plant pairs whose bounds meet that `budget` bytes hold (kBytesPerPlantPair each).
inline std::uint64_t most_plant_pairs(std::size_t budget) {
  return static_cast<std::uint64_t>(static_cast<double>(budget) / kBytesPerPlantPair);
}
/// Throws std::runtime_error: more than `most` plant pairs meet, more than `budget` bytes hold.
/// Both backends call it before their plant level's list is made (count_plant_pairs).
[[noreturn]] void refuse_plant_pairs(std::uint64_t most, std::size_t budget);

/// Throws std::runtime_error when resolving from `contacts` contacts would not fit in `limit`
/// (0: the memory available).
void check_resolution_fits(std::size_t contacts, std::size_t limit);

/// A ceiling on the process's resident memory for work whose size shows only as it grows:
/// resolution's candidates each carry their subtree, so a long chain turning (a vine of
/// thousands of segments coiled on itself) needs far more than the per-contact estimate above
/// (21.5 GB for 163,680 contacts of one 2,000-segment coil). The ceiling is what is resident when
/// it is set plus 90 % of the budget; the work checks it as it goes and stops with a clear error
/// instead of an out-of-memory kill. Like the other bounds it depends on the machine (what is
/// available, and the threads and lanes that hold candidates at once): a run it stops would
/// otherwise have taken the machine's last memory; the runs that finish give the same files.
class MemoryCeiling {
 public:
  /// `limit`: as memory_budget's (0: the memory available; no ceiling where unknown).
  explicit MemoryCeiling(std::size_t limit);
  /// Whether the process holds more than the ceiling now (reads /proc/self/statm).
  bool over() const;
  /// Throws std::runtime_error naming `what` grew past the ceiling.
  [[noreturn]] void refuse(const char* what) const;

 private:
  std::size_t ceiling_ = 0;  // 0: none
  std::size_t budget_ = 0;
  bool limited_ = false;  // the budget is a limit given, not the memory available
};

}  // namespace canopy
