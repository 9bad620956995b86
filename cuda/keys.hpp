#pragma once
/// Sorting, de-duplicating and compacting 64-bit keys on the device (CUB radix sort and select,
/// behind plain functions so that host files need not include CUB). Keys pack two 32-bit ids,
/// high word first, so their order is the order of (first id, second id): plant pairs (p, q) and
/// organ pairs (a, b) sort the way the CPU backend sorts them.
#include "cuda/device_buffer.hpp"
#include "geometry/hd.hpp"

#include <cstddef>
#include <cstdint>

namespace canopy::cuda {

/// The key of the id pair (hi, lo).
CANOPY_HD constexpr std::uint64_t pair_key(std::uint32_t hi, std::uint32_t lo) {
  return std::uint64_t{hi} << 32 | lo;
}
CANOPY_HD constexpr std::uint32_t key_hi(std::uint64_t k) { return static_cast<std::uint32_t>(k >> 32); }
CANOPY_HD constexpr std::uint32_t key_lo(std::uint64_t k) { return static_cast<std::uint32_t>(k); }

/// The operations, with CUB's scratch memory owned here and grown as needed.
class KeyOps {
 public:
  /// Scratch bytes the largest of the operations below needs for n keys.
  static std::size_t scratch_bytes(std::size_t n);
  /// out = in sorted (n keys).
  void sort(const std::uint64_t* in, std::uint64_t* out, std::size_t n);
  /// out keys = in keys sorted, values carried along.
  void sort_pairs(const std::uint64_t* keys_in, std::uint64_t* keys_out, const std::uint32_t* values_in,
                  std::uint32_t* values_out, std::size_t n);
  /// out keys = 32-bit keys sorted (stable: equal keys keep their order), values carried along.
  void sort_pairs(const std::uint32_t* keys_in, std::uint32_t* keys_out, const std::uint64_t* values_in,
                  std::uint64_t* values_out, std::size_t n);
  /// out = the sorted keys `in` without repeats; returns how many.
  std::size_t unique(const std::uint64_t* in, std::uint64_t* out, std::size_t n);
  /// out = the keys whose flag is set, in order; returns how many.
  std::size_t select(const std::uint64_t* in, const std::uint8_t* flags, std::uint64_t* out, std::size_t n);
  /// Gives the scratch memory back (under a device memory budget).
  void release() { scratch_.resize(0); }
  /// Device bytes held (scratch).
  std::size_t bytes() const { return scratch_.size() + count_.size() * sizeof(long long); }

 private:
  void* scratch(std::size_t bytes);
  /// A CUB call (scratch pointer, scratch bytes) made twice: for the scratch size, then to work.
  template <typename CubCall>
  void call(CubCall&& cub_call);
  std::size_t selected();
  DeviceBuffer<std::uint8_t> scratch_;
  DeviceBuffer<long long> count_;
};

}  // namespace canopy::cuda
