#include "cuda/light_raster.hpp"

#include "cuda/device_buffer.hpp"
#include "light/raster.hpp"

#include <algorithm>
#include <cstdint>

namespace canopy::cuda {
namespace {

/// A cell keeps the largest key put to it: the highest triangle over its point.
struct AtomicPut {
  unsigned long long* cells;
  __device__ void operator()(std::uint64_t c, std::uint64_t key) const {
    atomicMax(cells + c, static_cast<unsigned long long>(key));
  }
};

__global__ void draw_organs(light::RasterGrid g, light::RasterView v, unsigned long long* cells) {
  const std::uint64_t o = blockIdx.x * static_cast<std::uint64_t>(blockDim.x) + threadIdx.x;
  if (o >= v.organs) return;
  AtomicPut put{cells};
  light::raster_organ(g, v, o, put);
}

/// Fields counted in a block's shared memory before one global add each: the stand's counters
/// and kinds, and the layers' when there are few (every pair adds to them).
constexpr std::uint64_t kSmallSlots = 4 + 2 * light::kKinds;
constexpr std::int32_t kSharedLayers = 512;

/// Where a count goes: a block's shared counters for the small fields, else the global ones.
struct BlockCount {
  unsigned long long* local;  // shared: small slots, then the layers' (when shared)
  unsigned long long* counts;
  std::uint64_t plants, layers, layer0;
  bool shared_layers;
  __device__ void add(std::uint64_t s, unsigned long long n) const {
    if (s < kSmallSlots) atomicAdd(local + s, n);
    else if (shared_layers && s >= layer0) atomicAdd(local + kSmallSlots + (s - layer0), n);
    else atomicAdd(counts + s, n);
  }
};

/// A thread's last few counters, summed before they go out: neighbouring cells mostly hit the
/// same plant, kind and layer, so a run of pairs makes a few atomic adds instead of one a count.
struct ThreadCount {
  static constexpr int kWays = 8;
  const BlockCount& to;
  std::uint64_t slot[kWays];
  unsigned long long n[kWays];
  int next = 0;
  __device__ explicit ThreadCount(const BlockCount& b) : to(b) {
    for (int w = 0; w < kWays; ++w) slot[w] = ~0ull, n[w] = 0;
  }
  __device__ void operator()(light::TallyField f, std::uint64_t i) {
    const std::uint64_t s = light::tally_slot(f, i, to.plants, to.layers);
    for (int w = 0; w < kWays; ++w)
      if (slot[w] == s) {
        ++n[w];
        return;
      }
    if (n[next]) to.add(slot[next], n[next]);
    slot[next] = s, n[next] = 1;
    next = (next + 1) % kWays;
  }
  __device__ void flush() {
    for (int w = 0; w < kWays; ++w)
      if (n[w]) to.add(slot[w], n[w]), n[w] = 0;
  }
};

/// Pairs a thread counts one after another (along a row: the same plants, kinds and layers).
constexpr std::uint64_t kRun = 32;

__global__ void count_cells(light::RasterGrid g, const unsigned long long* cells, const std::int32_t* plant,
                            const std::uint8_t* kind, double layer_m, std::int32_t layers,
                            std::uint64_t plants, unsigned long long* counts) {
  extern __shared__ unsigned long long local[];
  const bool shared_layers = layers <= kSharedLayers;
  const std::uint64_t n_local = kSmallSlots + (shared_layers ? 2 * static_cast<std::uint64_t>(layers) : 0);
  for (std::uint64_t i = threadIdx.x; i < n_local; i += blockDim.x) local[i] = 0;
  __syncthreads();
  const std::uint64_t layer0 = light::tally_slot(light::TallyField::layer, 0, plants, layers);
  const BlockCount block{local, counts, plants, static_cast<std::uint64_t>(layers), layer0, shared_layers};
  ThreadCount count(block);
  const auto half = static_cast<std::uint64_t>(g.nx / 2), pairs = half * static_cast<std::uint64_t>(g.ny);
  const std::uint64_t runs = (pairs + kRun - 1) / kRun;
  for (std::uint64_t r = blockIdx.x * static_cast<std::uint64_t>(blockDim.x) + threadIdx.x; r < runs;
       r += static_cast<std::uint64_t>(gridDim.x) * blockDim.x) {
    const std::uint64_t end = r * kRun + kRun < pairs ? r * kRun + kRun : pairs;
    for (std::uint64_t p = r * kRun; p < end; ++p) {
      const std::uint64_t c = (p / half) * static_cast<std::uint64_t>(g.nx) + 2 * (p % half);
      const unsigned long long ka = cells[c], kb = cells[c + 1];
      const light::Outcome a =
          light::hit_outcome(light::key_organ(ka), light::key_height(ka), plant, kind, layer_m, layers);
      const light::Outcome b =
          light::hit_outcome(light::key_organ(kb), light::key_height(kb), plant, kind, layer_m, layers);
      light::count_ray(a, count);
      light::count_ray(b, count);
      light::count_pair(a, b, count);
    }
  }
  count.flush();
  __syncthreads();
  for (std::uint64_t i = threadIdx.x; i < n_local; i += blockDim.x)
    if (local[i]) atomicAdd(counts + (i < kSmallSlots ? i : layer0 + (i - kSmallSlots)), local[i]);
}

}  // namespace

struct LightRaster::Impl {
  int device = 0;
  std::string name;
  std::uint64_t generation = 0;  // of the stand uploaded (0: none)
  DeviceBuffer<Vec3f> positions;
  DeviceBuffer<std::uint32_t> indices, tri_first, tri_count, vertex_first;
  DeviceBuffer<Affine3f> transforms;
  DeviceBuffer<std::int16_t> slot;
  DeviceBuffer<std::int32_t> plant;
  DeviceBuffer<std::uint8_t> kind;
  DeviceBuffer<unsigned long long> counts;
  int multiprocessors = 1;
  DeviceBuffer<Vec3d> offset;
  DeviceBuffer<unsigned long long> cells;
  light::RasterView view;

  template <typename T>
  static void put(DeviceBuffer<T>& b, const T* src, std::uint64_t n) {
    b.resize(n);
    b.upload_at(0, src, n);
  }
  void upload(const light::RasterView& v) {
    if (v.generation != 0 && v.generation == generation) return;
    generation = 0;  // a failed upload leaves no stand behind
    put(positions, v.positions, v.vertices);
    put(indices, v.indices, 3 * v.mesh_triangles);
    put(tri_first, v.slot_tri_first, v.slots);
    put(tri_count, v.slot_tri_count, v.slots);
    put(vertex_first, v.slot_vertex_first, v.slots);
    put(transforms, v.transforms, v.organs);
    put(slot, v.slot, v.organs);
    put(plant, v.plant, v.organs);
    put(kind, v.kind, v.organs);
    put(offset, v.offset, v.plants);
    view = v;
    view.positions = positions.get(), view.indices = indices.get();
    view.slot_tri_first = tri_first.get(), view.slot_tri_count = tri_count.get();
    view.slot_vertex_first = vertex_first.get();
    view.transforms = transforms.get(), view.slot = slot.get(), view.plant = plant.get();
    view.kind = kind.get();
    view.offset = offset.get();
    generation = v.generation;
  }
};

LightRaster::LightRaster(int device) : impl_(std::make_unique<Impl>()) {
  impl_->device = device;
  CANOPY_CUDA_CHECK(cudaSetDevice(device));
  cudaDeviceProp p{};
  CANOPY_CUDA_CHECK(cudaGetDeviceProperties(&p, device));
  impl_->name = p.name;
  impl_->multiprocessors = p.multiProcessorCount;
}

LightRaster::~LightRaster() = default;

std::string LightRaster::name() const { return impl_->name; }

bool LightRaster::fits(std::uint64_t cells) const {
  CANOPY_CUDA_CHECK(cudaSetDevice(impl_->device));
  std::size_t free = 0, total = 0;
  CANOPY_CUDA_CHECK(cudaMemGetInfo(&free, &total));
  // The cells held now are freed when a larger pass takes their place; a tenth stays spare.
  const double have = static_cast<double>(free) + 8.0 * static_cast<double>(impl_->cells.size());
  return 8.0 * static_cast<double>(cells) <= 0.9 * have;
}

void LightRaster::count(const light::RasterView& v, const light::RasterGrid& g, double layer_m,
                        std::int32_t layers, std::uint64_t* counts) {
  Impl& m = *impl_;
  CANOPY_CUDA_CHECK(cudaSetDevice(m.device));
  m.upload(v);
  const auto n = static_cast<std::size_t>(g.nx) * static_cast<std::size_t>(g.ny);
  m.cells.grow(n);
  CANOPY_CUDA_CHECK(cudaMemset(m.cells.get(), 0, n * sizeof(unsigned long long)));
  if (v.organs) {
    constexpr unsigned kBlock = 128;
    const auto blocks = static_cast<unsigned>((v.organs + kBlock - 1) / kBlock);
    draw_organs<<<blocks, kBlock>>>(g, m.view, m.cells.get());
    CANOPY_CUDA_CHECK_LAUNCH("draw_organs (light's cells)");
  }
  const std::uint64_t slots = light::tally_slots(v.plants, static_cast<std::uint64_t>(layers));
  m.counts.grow(slots);
  CANOPY_CUDA_CHECK(cudaMemset(m.counts.get(), 0, slots * sizeof(unsigned long long)));
  constexpr unsigned kBlock = 256;
  const std::uint64_t runs = (n / 2 + kRun - 1) / kRun;
  const auto blocks = static_cast<unsigned>(std::max<std::uint64_t>(
      1, std::min<std::uint64_t>((runs + kBlock - 1) / kBlock, 16ull * m.multiprocessors)));
  const std::size_t shared =
      (kSmallSlots + (layers <= kSharedLayers ? 2 * static_cast<std::size_t>(layers) : 0)) *
      sizeof(unsigned long long);
  count_cells<<<blocks, kBlock, shared>>>(g, m.cells.get(), m.view.plant, m.view.kind, layer_m, layers,
                                          v.plants, m.counts.get());
  CANOPY_CUDA_CHECK_LAUNCH("count_cells (light's tally)");
  CANOPY_CUDA_CHECK(
      cudaMemcpy(counts, m.counts.get(), slots * sizeof(std::uint64_t), cudaMemcpyDeviceToHost));
}

}  // namespace canopy::cuda
