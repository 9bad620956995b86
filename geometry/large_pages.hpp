#pragma once
/// Memory for large arrays in 2 MiB pages where the system offers them (Linux transparent huge
/// pages in "madvise" mode, which Debian and Ubuntu kernels default to): an array of hundreds of
/// megabytes then faults in 512 times fewer pages. With the planning's tables kept from round
/// to round and a padded heap top, it makes 10,000-plant CUDA resolutions on a 16-core host
/// faster (bench_resolve: about 1.2x, the three measured together).
#include <cstddef>

namespace canopy {

/// Arrays of at least this many bytes are mapped on their own, in large pages where possible.
inline constexpr std::size_t kLargeArrayBytes = std::size_t{4} << 20;

/// `bytes` (at least kLargeArrayBytes) of fresh zeroed memory aligned to 2 MiB, with the kernel
/// asked for huge pages; throws std::bad_alloc where the system has no room.
void* map_large(std::size_t bytes);
/// Gives back what map_large(bytes) returned.
void unmap_large(void* p, std::size_t bytes) noexcept;
/// Asks for huge pages on the whole 2 MiB pages inside [p, p + bytes) of memory not touched yet
/// (a std::vector's reserve() of kLargeArrayBytes or more, before it is resized): for an array
/// of a type the program cannot give map_large's allocator (geometry/first_touch.hpp). Advice
/// only; nothing happens for smaller ranges or where the system refuses.
void advise_large_pages(void* p, std::size_t bytes) noexcept;

}  // namespace canopy
