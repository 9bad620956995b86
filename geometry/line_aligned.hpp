#pragma once
/// Arrays that start on a cache line (64 bytes), for data the CPU backend reads in lanes of 8
/// floats (32-byte loads): organ and cluster boxes and LCD boxes in lanes
/// (collision/lanes/organ_lanes.hpp), a prototype's corners and a posed organ's triangles in lanes
/// (geometry/prototype.hpp, collision/exact.hpp). From the heap's 16-byte alignment, every other
/// 32-byte load of such an array crossed into a second line, and a 64-byte record (an OBB)
/// spanned two.
#include <cstddef>
#include <memory>
#include <new>
#include <vector>

namespace canopy {

inline constexpr std::size_t kCacheLine = 64;

template <class T>
struct LineAlignedAllocator {
  using value_type = T;
  LineAlignedAllocator() = default;
  template <class U>
  LineAlignedAllocator(const LineAlignedAllocator<U>&) noexcept {}
  T* allocate(std::size_t n) {
    if (n > static_cast<std::size_t>(-1) / sizeof(T)) throw std::bad_array_new_length();
    return static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t(kCacheLine)));
  }
  void deallocate(T* p, std::size_t) noexcept { ::operator delete(p, std::align_val_t(kCacheLine)); }
  template <class U>
  bool operator==(const LineAlignedAllocator<U>&) const noexcept {
    return true;
  }
};

/// A std::vector whose elements start on a cache line.
template <class T>
using LineAlignedVector = std::vector<T, LineAlignedAllocator<T>>;

}  // namespace canopy
