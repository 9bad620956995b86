#pragma once
/// Host-side helpers for lists the kernels fill on the device: a launch into a list of unknown
/// length (grown and run again when it overflows), and a download appended to a host vector.
#include "cuda/detect_kernels.hpp"
#include "cuda/device_buffer.hpp"
#include "cuda/event_timer.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace canopy::cuda {

/// Items one launch may list (counts and indices are 32-bit in the kernels).
inline constexpr std::size_t kMaxItems = 0x7fffffff;

/// Runs `launch` into `out` with room for `guess` items (at least what `out` holds unless
/// `tight`), at most `limit`; when more were found and they fit the limit, grows the buffer and
/// runs again. Returns the items found, which exceed `limit` when they do not fit (then nothing
/// usable is in `out`).
template <typename T, typename Launch>
std::size_t collect(DeviceBuffer<T>& out, DeviceBuffer<Counters>& counters, Counters& host, std::size_t guess,
                    std::size_t limit, bool tight, EventTimer& timer, Launch&& launch) {
  std::size_t capacity =
      std::max<std::size_t>(std::min(tight ? guess : std::max(guess, out.size()), limit), 1);
  for (;;) {
    out.fit(capacity, tight);
    CANOPY_CUDA_CHECK(cudaMemset(counters.get(), 0, sizeof(Counters)));
    timer.start();
    launch(out.get(), static_cast<unsigned long long>(capacity));
    timer.stop();
    CANOPY_CUDA_CHECK(cudaMemcpy(&host, counters.get(), sizeof host, cudaMemcpyDeviceToHost));
    const auto found = static_cast<std::size_t>(host.appended);
    if (found <= capacity || found > limit) return found;
    capacity = found;
  }
}

/// Appends the first n items of a device list to a host vector, through page-locked memory and
/// a copy on all cores.
template <typename T>
void append_download(std::vector<T>& to, const T* from, std::size_t n, PinnedBuffer<T>& staging) {
  if (!n) return;
  staging.grow(n);
  CANOPY_CUDA_CHECK(cudaMemcpy(staging.get(), from, n * sizeof(T), cudaMemcpyDeviceToHost));
  const std::size_t at = to.size();
  to.resize(at + n);
  constexpr std::size_t kChunk = 16384;
  const auto chunks = static_cast<std::int64_t>((n + kChunk - 1) / kChunk);
#pragma omp parallel for schedule(static)
  for (std::int64_t c = 0; c < chunks; ++c) {
    const std::size_t lo = static_cast<std::size_t>(c) * kChunk, hi = std::min(n, lo + kChunk);
    std::copy(staging.get() + lo, staging.get() + hi, to.begin() + static_cast<std::ptrdiff_t>(at + lo));
  }
}

}  // namespace canopy::cuda
