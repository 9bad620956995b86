#pragma once
/// An allocator for large arrays that a parallel loop fills: elements made without arguments are
/// left as the memory comes instead of being zeroed, so the pages of a 200 MB array (an OBB per
/// organ of a 10,000-plant stand) are first touched, and faulted in, by the threads that write
/// them rather than by one thread zeroing them beforehand. Only for numbers and implicit-lifetime
/// aggregates (plain structs of numbers) that the caller writes in full before reading.
///
/// With `Large`, arrays of kLargeArrayBytes or more are mapped on their own in large pages where
/// the system offers them (geometry/large_pages.hpp): a fault then brings in 2 MiB instead of 4
/// KiB, for arrays read many times over (OBBs). Otherwise, and for smaller ones, they come from
/// the heap on a cache line (geometry/line_aligned.hpp), as the mapped ones start: arrays written
/// once and read once or twice (the tree's shape: the 10,000-plant stand's 144 MB in 22-29 ms
/// on 16 cores with small pages, 24-32 ms in large ones; on a 2-core VM, where a large page's
/// first fault waits for the hypervisor, 0.11 s against 0.28-0.34 s).
#include "geometry/large_pages.hpp"
#include "geometry/line_aligned.hpp"

#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace canopy {

template <class T, bool Large = true>
struct FirstTouchAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = FirstTouchAllocator<U, Large>;
  };
  FirstTouchAllocator() = default;
  template <class U>
  FirstTouchAllocator(const FirstTouchAllocator<U, Large>&) noexcept {}
  T* allocate(std::size_t n) {
    if (n > static_cast<std::size_t>(-1) / sizeof(T)) throw std::bad_array_new_length();
    // Below the large arrays' size, from the heap on a cache line (a 64-byte OBB then spans one).
    if (!mapped(n)) return LineAlignedAllocator<T>().allocate(n);
    return static_cast<T*>(map_large(n * sizeof(T)));
  }
  void deallocate(T* p, std::size_t n) noexcept {
    if (!mapped(n)) LineAlignedAllocator<T>().deallocate(p, n);
    else unmap_large(p, n * sizeof(T));
  }
  static bool mapped(std::size_t n) { return Large && n * sizeof(T) >= kLargeArrayBytes; }
  template <class U>
  void construct(U*) noexcept {
    static_assert((std::is_aggregate_v<U> || std::is_arithmetic_v<U>)&&std::is_trivially_copyable_v<U> &&
                      std::is_trivially_destructible_v<U>,
                  "only plain structs of numbers are left unwritten");
  }
  template <class U, class... A>
  void construct(U* p, A&&... a) {
    std::construct_at(p, std::forward<A>(a)...);
  }
};

/// Arrays that a parallel loop fills (see above): in large pages, and in the heap's pages.
template <class T>
using FirstTouchVector = std::vector<T, FirstTouchAllocator<T>>;
template <class T>
using UnzeroedVector = std::vector<T, FirstTouchAllocator<T, false>>;

}  // namespace canopy
