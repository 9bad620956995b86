#pragma once
/// An allocator for large arrays that a parallel loop fills: elements made without arguments are
/// left as the memory comes instead of being zeroed, so the pages of a 200 MB array (an OBB per
/// organ of a 10,000-plant stand) are first touched, and faulted in, by the threads that write
/// them rather than by one thread zeroing them beforehand. Only for numbers and implicit-lifetime
/// aggregates (plain structs of numbers) that the caller writes in full before reading.
#include <memory>
#include <type_traits>
#include <utility>

namespace canopy {

template <class T>
struct FirstTouchAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = FirstTouchAllocator<U>;
  };
  FirstTouchAllocator() = default;
  template <class U>
  FirstTouchAllocator(const FirstTouchAllocator<U>&) noexcept {}
  template <class U>
  void construct(U*) noexcept {
    static_assert((std::is_aggregate_v<U> || std::is_arithmetic_v<U>) && std::is_trivially_copyable_v<U> &&
                      std::is_trivially_destructible_v<U>,
                  "only plain structs of numbers are left unwritten");
  }
  template <class U, class... A>
  void construct(U* p, A&&... a) {
    std::construct_at(p, std::forward<A>(a)...);
  }
};

}  // namespace canopy
