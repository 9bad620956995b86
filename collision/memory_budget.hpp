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

}  // namespace canopy
