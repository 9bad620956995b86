// KeyOps: CUB radix sort, unique and flagged selection on 64-bit keys.
#include "cuda/check.hpp"
#include "cuda/keys.hpp"

#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_select.cuh>

#include <algorithm>

namespace canopy::cuda {

std::size_t KeyOps::scratch_bytes(std::size_t n) {
  const auto items = static_cast<long long>(n);
  std::size_t a = 0, b = 0, c = 0, d = 0;
  CANOPY_CUDA_CHECK(cub::DeviceRadixSort::SortKeys(nullptr, a, static_cast<const std::uint64_t*>(nullptr),
                                                   static_cast<std::uint64_t*>(nullptr), items));
  CANOPY_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(
      nullptr, b, static_cast<const std::uint64_t*>(nullptr), static_cast<std::uint64_t*>(nullptr),
      static_cast<const std::uint32_t*>(nullptr), static_cast<std::uint32_t*>(nullptr), items));
  CANOPY_CUDA_CHECK(cub::DeviceSelect::Unique(nullptr, c, static_cast<const std::uint64_t*>(nullptr),
                                              static_cast<std::uint64_t*>(nullptr),
                                              static_cast<long long*>(nullptr), items));
  CANOPY_CUDA_CHECK(cub::DeviceSelect::Flagged(
      nullptr, d, static_cast<const std::uint64_t*>(nullptr), static_cast<const std::uint8_t*>(nullptr),
      static_cast<std::uint64_t*>(nullptr), static_cast<long long*>(nullptr), items));
  std::size_t e = 0;
  CANOPY_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(
      nullptr, e, static_cast<const std::uint32_t*>(nullptr), static_cast<std::uint32_t*>(nullptr),
      static_cast<const std::uint64_t*>(nullptr), static_cast<std::uint64_t*>(nullptr), items));
  return std::max({a, b, c, d, e}) + sizeof(long long);
}

void* KeyOps::scratch(std::size_t bytes) {
  if (scratch_.size() < bytes) scratch_.resize(bytes);
  if (count_.size() == 0) count_.resize(1);
  return scratch_.get();
}

std::size_t KeyOps::selected() {
  long long n = 0;
  CANOPY_CUDA_CHECK(cudaMemcpy(&n, count_.get(), sizeof n, cudaMemcpyDeviceToHost));
  return static_cast<std::size_t>(n);
}

template <typename CubCall>
void KeyOps::call(CubCall&& cub_call) {
  std::size_t bytes = 0;
  CANOPY_CUDA_CHECK(cub_call(nullptr, bytes));  // the scratch it needs, then the work
  void* s = scratch(bytes);
  CANOPY_CUDA_CHECK(cub_call(s, bytes));
}

void KeyOps::sort(const std::uint64_t* in, std::uint64_t* out, std::size_t n) {
  if (!n) return;
  const auto items = static_cast<long long>(n);
  call([&](void* s, std::size_t& bytes) { return cub::DeviceRadixSort::SortKeys(s, bytes, in, out, items); });
}

namespace {
/// CUB's key-value radix sort, for both key/value type pairs KeyOps offers.
template <typename K, typename V>
auto sort_by_key(const K* keys_in, K* keys_out, const V* values_in, V* values_out, long long items) {
  return [=](void* s, std::size_t& bytes) {
    return cub::DeviceRadixSort::SortPairs(s, bytes, keys_in, keys_out, values_in, values_out, items);
  };
}
}  // namespace

void KeyOps::sort_pairs(const std::uint64_t* keys_in, std::uint64_t* keys_out, const std::uint32_t* values_in,
                        std::uint32_t* values_out, std::size_t n) {
  if (n) call(sort_by_key(keys_in, keys_out, values_in, values_out, static_cast<long long>(n)));
}

void KeyOps::sort_pairs(const std::uint32_t* keys_in, std::uint32_t* keys_out, const std::uint64_t* values_in,
                        std::uint64_t* values_out, std::size_t n) {
  if (n) call(sort_by_key(keys_in, keys_out, values_in, values_out, static_cast<long long>(n)));
}

std::size_t KeyOps::unique(const std::uint64_t* in, std::uint64_t* out, std::size_t n) {
  if (!n) return 0;
  const auto items = static_cast<long long>(n);
  call([&](void* s, std::size_t& bytes) {
    return cub::DeviceSelect::Unique(s, bytes, in, out, count_.get(), items);
  });
  return selected();
}

std::size_t KeyOps::select(const std::uint64_t* in, const std::uint8_t* flags, std::uint64_t* out,
                           std::size_t n) {
  if (!n) return 0;
  const auto items = static_cast<long long>(n);
  call([&](void* s, std::size_t& bytes) {
    return cub::DeviceSelect::Flagged(s, bytes, in, flags, out, count_.get(), items);
  });
  return selected();
}

}  // namespace canopy::cuda
