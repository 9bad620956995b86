// The device plant grid: cells, then pairs by a binary search of the sorted cells.
#include "collision/mbvt_fit.hpp"
#include "cuda/append.cuh"
#include "cuda/check.hpp"
#include "cuda/grid_kernels.hpp"
#include "cuda/keys.hpp"

namespace canopy::cuda {
namespace {

constexpr int kThreads = 128;
unsigned blocks(std::uint32_t n) { return (n + kThreads - 1) / kThreads; }

/// Cell coordinates from the grid corner: non-negative, and below 2^31 (the host sizes cells so).
__device__ void cell_of(const PlantOrigin& o, double x0, double y0, double cell, std::uint32_t& ix,
                        std::uint32_t& iy) {
  ix = static_cast<std::uint32_t>(floor((o.x - x0) / cell));
  iy = static_cast<std::uint32_t>(floor((o.y - y0) / cell));
}

__global__ void plant_cells_kernel(const PlantOrigin* origins, std::uint32_t n, double x0, double y0,
                                   double cell, std::uint64_t* keys, std::uint32_t* ids) {
  const std::uint32_t p = blockIdx.x * blockDim.x + threadIdx.x;
  if (p >= n) return;
  std::uint32_t ix, iy;
  cell_of(origins[p], x0, y0, cell, ix, iy);
  keys[p] = pair_key(ix, iy);
  ids[p] = p;
}

/// The first position in the sorted cells whose key is not below `key`.
__device__ std::uint32_t lower_bound(const std::uint64_t* cells, std::uint32_t n, std::uint64_t key) {
  std::uint32_t lo = 0, hi = n;
  while (lo < hi) {
    const std::uint32_t mid = lo + (hi - lo) / 2;
    if (cells[mid] < key) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}

__global__ void plant_pairs_kernel(GridView g, std::uint64_t* out, unsigned long long capacity, Counters* c) {
  const std::uint32_t p = blockIdx.x * blockDim.x + threadIdx.x;
  if (p >= g.n) return;
  const PlantOrigin o = g.origins[p];
  const bool on = !g.active || g.active[p];
  std::uint32_t ix, iy;
  cell_of(o, g.x0, g.y0, g.cell, ix, iy);
  unsigned long long found = 0;
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy) {
      if ((ix == 0 && dx < 0) || (iy == 0 && dy < 0)) continue;
      const std::uint64_t key = pair_key(ix + dx, iy + dy);
      for (std::uint32_t j = lower_bound(g.cells, g.n, key); j < g.n && g.cells[j] == key; ++j) {
        const std::uint32_t q = g.members[j];
        if (q <= p || !(on || g.active[q])) continue;
        const PlantOrigin oq = g.origins[q];
        if (!plant_bounds_meet(g.plants[p], g.plants[q], oq.x - o.x, oq.y - o.y)) continue;
        append(out, capacity, c, pair_key(p, q));
        ++found;
      }
    }
  if (found) atomicAdd(&c->between, found);
  if (on && g.self[p]) {
    append(out, capacity, c, pair_key(p, p));
    atomicAdd(&c->within, 1ull);
  }
}

}  // namespace

void launch_plant_cells(const PlantOrigin* origins, std::uint32_t n, double x0, double y0, double cell,
                        std::uint64_t* keys, std::uint32_t* ids) {
  if (!n) return;
  plant_cells_kernel<<<blocks(n), kThreads>>>(origins, n, x0, y0, cell, keys, ids);
  CANOPY_CUDA_CHECK_LAUNCH("plant_cells_kernel");
}

void launch_plant_pairs(const GridView& g, std::uint64_t* out, unsigned long long capacity,
                        Counters* counters) {
  if (!g.n) return;
  plant_pairs_kernel<<<blocks(g.n), kThreads>>>(g, out, capacity, counters);
  CANOPY_CUDA_CHECK_LAUNCH("plant_pairs_kernel");
}

}  // namespace canopy::cuda
