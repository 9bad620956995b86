#include "geometry/large_pages.hpp"

#include <cstdint>
#include <cstdlib>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace canopy {
namespace {

constexpr std::size_t kHugePage = std::size_t{2} << 20;

std::size_t rounded(std::size_t bytes) { return (bytes + kHugePage - 1) / kHugePage * kHugePage; }

}  // namespace

#if defined(__linux__)

void* map_large(std::size_t bytes) {
  // Mapped with a huge page of slack, then trimmed to a 2 MiB-aligned range: only aligned
  // ranges can be backed by huge pages.
  const std::size_t size = rounded(bytes), span = size + kHugePage;
  void* raw = mmap(nullptr, span, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (raw == MAP_FAILED) throw std::bad_alloc();
  const auto base = reinterpret_cast<std::uintptr_t>(raw);
  const std::uintptr_t aligned = (base + kHugePage - 1) / kHugePage * kHugePage;
  if (aligned > base) munmap(raw, aligned - base);
  if (const std::uintptr_t tail = base + span - (aligned + size))
    munmap(reinterpret_cast<void*>(aligned + size), tail);
  void* p = reinterpret_cast<void*>(aligned);
#ifdef MADV_HUGEPAGE
  madvise(p, size, MADV_HUGEPAGE);  // advice only: where it is refused the pages are small
#endif
  return p;
}

void unmap_large(void* p, std::size_t bytes) noexcept {
  if (p) munmap(p, rounded(bytes));
}

void advise_large_pages(void* p, std::size_t bytes) noexcept {
#ifdef MADV_HUGEPAGE
  if (!p || bytes < kLargeArrayBytes) return;
  const auto base = reinterpret_cast<std::uintptr_t>(p);
  const std::uintptr_t first = rounded(base), last = (base + bytes) / kHugePage * kHugePage;
  if (last > first) madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
#else
  (void)p, (void)bytes;
#endif
}

#else

void* map_large(std::size_t bytes) {
  void* p = std::aligned_alloc(kHugePage, rounded(bytes));
  if (!p) throw std::bad_alloc();
  return p;
}

void unmap_large(void* p, std::size_t) noexcept { std::free(p); }

void advise_large_pages(void*, std::size_t) noexcept {}

#endif

}  // namespace canopy
