#pragma once
/// The owner of a device array (RAII) and the views kernels take by value.
#include "cuda/check.hpp"
#include "cuda/pinned_upload.hpp"

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <utility>
#include <vector>

namespace canopy::cuda {

/// Bytes held in this process's device buffers (DeviceBuffer, StreamBuffer), now and at most:
/// the device memory a run needs beyond the CUDA context (bench_stand reports the peak).
class DeviceBytes {
 public:
  void add(std::size_t n) {
    const std::size_t now = now_.fetch_add(n) + n;
    for (std::size_t p = peak_.load(); now > p && !peak_.compare_exchange_weak(p, now);) {
    }
  }
  void sub(std::size_t n) { now_.fetch_sub(n); }
  std::size_t now() const { return now_.load(); }
  std::size_t peak() const { return peak_.load(); }

 private:
  std::atomic<std::size_t> now_{0}, peak_{0};
};
inline DeviceBytes& device_bytes() {
  static DeviceBytes bytes;
  return bytes;
}

template <typename T>
class DeviceBuffer {
 public:
  DeviceBuffer() = default;
  explicit DeviceBuffer(std::size_t n) { resize(n); }
  DeviceBuffer(const DeviceBuffer&) = delete;
  DeviceBuffer& operator=(const DeviceBuffer&) = delete;
  DeviceBuffer(DeviceBuffer&& o) noexcept : p_(std::exchange(o.p_, nullptr)), n_(std::exchange(o.n_, 0)) {}
  DeviceBuffer& operator=(DeviceBuffer&& o) noexcept {
    std::swap(p_, o.p_);
    std::swap(n_, o.n_);
    return *this;
  }
  ~DeviceBuffer() {
    if (p_) {
      cudaFree(p_);
      device_bytes().sub(n_ * sizeof(T));
    }
  }
  void resize(std::size_t n) {
    if (n == n_) return;
    if (p_) {
      CANOPY_CUDA_CHECK(cudaFree(p_));
      device_bytes().sub(n_ * sizeof(T));
    }
    p_ = nullptr;
    n_ = 0;
    if (n) {
      CANOPY_CUDA_CHECK(cudaMalloc(&p_, n * sizeof(T)));
      device_bytes().add(n * sizeof(T));
    }
    n_ = n;
  }
  /// Room for at least n items: reallocates only to grow (the contents are then lost).
  void grow(std::size_t n) {
    if (n > n_) resize(n);
  }
  /// Copies n items from the host to items [at, at + n).
  void upload_at(std::size_t at, const T* src, std::size_t n) {
    if (n) CANOPY_CUDA_CHECK(cudaMemcpy(p_ + at, src, n * sizeof(T), cudaMemcpyHostToDevice));
  }
  /// Room for n items, exactly when `tight` (a device memory budget is in force), else at least.
  void fit(std::size_t n, bool tight) { tight ? resize(n) : grow(n); }
  template <class Alloc>
  void upload(const std::vector<T, Alloc>& v) {
    resize(v.size());
    if (!v.empty()) CANOPY_CUDA_CHECK(cudaMemcpy(p_, v.data(), v.size() * sizeof(T), cudaMemcpyHostToDevice));
  }
  /// The same, queued on `via`: copied by via.finish() (v must stay as it is until then).
  template <class Alloc>
  void upload(const std::vector<T, Alloc>& v, PinnedUpload& via) {
    resize(v.size());
    via.copy(p_, v.data(), v.size() * sizeof(T));
  }
  std::vector<T> download(std::size_t n) const {
    std::vector<T> v(n);
    if (n) CANOPY_CUDA_CHECK(cudaMemcpy(v.data(), p_, n * sizeof(T), cudaMemcpyDeviceToHost));
    return v;
  }
  T* get() const { return p_; }
  std::size_t size() const { return n_; }

 private:
  T* p_ = nullptr;
  std::size_t n_ = 0;
};

/// The owner of a device array allocated and freed in a stream's order (cudaMallocAsync, from
/// the device's default pool): growing it never waits for the device, where cudaMalloc and
/// cudaFree wait for the work of every stream (of the other lanes too). Its contents are used
/// only by work queued in the same stream.
template <typename T>
class StreamBuffer {
 public:
  explicit StreamBuffer(cudaStream_t stream) : stream_(stream) {}
  StreamBuffer(const StreamBuffer&) = delete;
  StreamBuffer& operator=(const StreamBuffer&) = delete;
  ~StreamBuffer() {
    if (p_) {
      cudaFreeAsync(p_, stream_);
      device_bytes().sub(n_ * sizeof(T));
    }
  }
  /// Room for at least n items (the contents are then lost), at least half again the size.
  void grow(std::size_t n) { grow_keeping(n, 0); }
  /// Room for at least n items keeping the first `keep`, at least half again the size (an
  /// append-only table's appends then cost amortised constant copies).
  void grow_keeping(std::size_t n, std::size_t keep) {
    if (n <= n_) return;
    const std::size_t m = std::max(n, n_ + n_ / 2);
    T* bigger = nullptr;
    CANOPY_CUDA_CHECK(cudaMallocAsync(reinterpret_cast<void**>(&bigger), m * sizeof(T), stream_));
    device_bytes().add(m * sizeof(T));
    if (keep) {
      if (const cudaError_t e =
              cudaMemcpyAsync(bigger, p_, keep * sizeof(T), cudaMemcpyDeviceToDevice, stream_);
          e != cudaSuccess) {
        cudaFreeAsync(bigger, stream_);  // this buffer stays as it was
        device_bytes().sub(m * sizeof(T));
        ::canopy::cuda::check(e, "cudaMemcpyAsync (keeping a stream buffer's entries as it grows)", __FILE__,
                              __LINE__);
      }
    }
    if (p_) {
      CANOPY_CUDA_CHECK(cudaFreeAsync(p_, stream_));
      device_bytes().sub(n_ * sizeof(T));
    }
    p_ = bigger;
    n_ = m;
  }
  T* get() const { return p_; }
  std::size_t size() const { return n_; }

 private:
  cudaStream_t stream_;
  T* p_ = nullptr;
  std::size_t n_ = 0;
};

/// A queue of device work of its own (RAII) that does not wait for the default stream's.
class Stream {
 public:
  Stream() { CANOPY_CUDA_CHECK(cudaStreamCreateWithFlags(&s_, cudaStreamNonBlocking)); }
  Stream(const Stream&) = delete;
  Stream& operator=(const Stream&) = delete;
  ~Stream() { cudaStreamDestroy(s_); }
  cudaStream_t get() const { return s_; }
  void synchronize() const { CANOPY_CUDA_CHECK(cudaStreamSynchronize(s_)); }

 private:
  cudaStream_t s_ = nullptr;
};

/// Page-locked host memory (RAII), which the device copies into at full speed; grows only.
template <typename T>
class PinnedBuffer {
 public:
  PinnedBuffer() = default;
  PinnedBuffer(const PinnedBuffer&) = delete;
  PinnedBuffer& operator=(const PinnedBuffer&) = delete;
  ~PinnedBuffer() {
    if (p_) cudaFreeHost(p_);
  }
  void grow(std::size_t n) {
    if (n <= n_) return;
    if (p_) CANOPY_CUDA_CHECK(cudaFreeHost(p_));
    p_ = nullptr;
    n_ = 0;
    CANOPY_CUDA_CHECK(cudaMallocHost(&p_, n * sizeof(T)));
    n_ = n;
  }
  T* get() const { return p_; }
  std::size_t size() const { return n_; }

 private:
  T* p_ = nullptr;
  std::size_t n_ = 0;
};

}  // namespace canopy::cuda
