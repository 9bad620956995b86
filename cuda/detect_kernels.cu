// The CUDA detection kernels. Same contact semantics as collision/detect_cpu.cpp: the same
// LCD, OBB and triangle predicates (geometry/*.hpp, CANOPY_HD), compiled with --fmad=false.
#include "collision/contacts.hpp"
#include "collision/lcd_descent.hpp"
#include "collision/mbvt_fit.hpp"
#include "collision/organ_blocks.hpp"
#include "cuda/append.cuh"
#include "cuda/check.hpp"
#include "cuda/detect_kernels.hpp"
#include "cuda/keys.hpp"
#include "cuda/organ_pair_test.cuh"
#include "geometry/lcd.hpp"
#include "geometry/obb.hpp"
#include "geometry/triangle_test.hpp"

namespace canopy::cuda {
namespace {

constexpr int kThreads = 128;

__global__ void work_items_kernel(StandView v, const std::uint64_t* keys, std::uint32_t n, WorkItem* out) {
  const std::uint32_t k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= n) return;
  const auto p = static_cast<std::int32_t>(key_hi(keys[k])), q = static_cast<std::int32_t>(key_lo(keys[k]));
  out[k] = WorkItem{p, q, offset_between(v, p, q)};
}

/// Threads per plant pair in the cluster-pairs kernel: fewer leave the GPU idle behind the
/// busiest plant pairs, more give each thread too little to do (bench_detect_cuda: 4 about 1.4x
/// faster than 1, and faster than 8, 16 and 32).
constexpr int kClusterLanes = 4;

/// kClusterLanes threads per plant pair: lane l takes the clusters l, l + kClusterLanes, ... of
/// plant p against the clusters of plant q (the axis-aligned pre-tests leave most of them little
/// to do, so one thread per plant pair would leave the GPU idle behind the busiest).
__global__ void cluster_pairs_kernel(StandView v, const WorkItem* work, std::uint32_t n_work,
                                     ClusterPair* out, unsigned long long capacity, Counters* c) {
  const std::uint64_t t = static_cast<std::uint64_t>(blockIdx.x) * blockDim.x + threadIdx.x;
  const auto w = static_cast<std::uint32_t>(t / kClusterLanes),
             lane = static_cast<std::uint32_t>(t % kClusterLanes);
  if (w >= n_work) return;
  const WorkItem it = work[w];
  const PlantBound pa = v.plants[it.p], pb = v.plants[it.q];
  unsigned long long found = 0;
  for (std::uint32_t i = pa.first_cluster + lane; i < pa.first_cluster + pa.cluster_count;
       i += kClusterLanes) {
    const Cluster ca = v.clusters[i];
    if (it.p != it.q && !boxes_meet(ca.box, pb.box, it.offset)) continue;  // pre-tests as on the CPU
    for (std::uint32_t j = it.p == it.q ? i : pb.first_cluster; j < pb.first_cluster + pb.cluster_count;
         ++j) {
      const Cluster& cb = v.clusters[j];
      if (i != j && !boxes_meet(ca.box, cb.box, it.offset)) continue;
      const bool meet = i == j ? organs_hold_free_pair(v.organs, v.cluster_organs, ca.first, ca.count)
                               : lcd_overlap(v.nodes[ca.root].box, v.nodes[cb.root].box, it.offset);
      if (!meet) continue;
      ++found;
      append(out, capacity, c, ClusterPair{w, i, j});
    }
  }
  if (found) atomicAdd(it.p == it.q ? &c->within : &c->between, found);
}

__global__ void organ_pairs_kernel(StandView v, const WorkItem* work, const ClusterPair* pairs,
                                   std::uint32_t n, std::uint64_t* out, unsigned long long capacity,
                                   Counters* c) {
  const std::uint32_t k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= n) return;
  const ClusterPair cp = pairs[k];
  const WorkItem it = work[cp.work];
  const Cluster ca = v.clusters[cp.a], cb = v.clusters[cp.b];
  // The pairs of collision/organ_blocks.hpp (organ boxes that meet), then not adjacent and OBBs
  // overlapping, as on the host: one conjunction, tested here in the order cheapest on the device,
  // the organ boxes last (each made from its OBB when asked for, by the host's function: the same
  // bits as the host's lanes), as most pairs fail the OBB test's sphere step on data it loads anyway.
  const auto box_of = [&](std::uint32_t pos) { return obb_aabb(v.obbs[v.cluster_organs[pos]]); };
  const auto test = [&](std::uint32_t x, std::uint32_t y) {
    const auto a = static_cast<std::int32_t>(v.cluster_organs[x]),
               b = static_cast<std::int32_t>(v.cluster_organs[y]);
    if (adjacent(v.organs[a], a, v.organs[b], b) || !obb_overlap(v.obbs[a], v.obbs[b], it.offset)) return;
    if (!boxes_meet(box_of(x), box_of(y), it.offset)) return;
    append(out, capacity, c,
           pair_key(static_cast<std::uint32_t>(a < b ? a : b), static_cast<std::uint32_t>(a < b ? b : a)));
  };
  if (cp.a == cp.b) {
    for (std::uint32_t x = ca.first; x < ca.first + ca.count; ++x)
      for (std::uint32_t y = x + 1; y < ca.first + ca.count; ++y) test(x, y);
    return;
  }
  descend_lcd_trees(v.nodes, ca.root, cb.root, it.offset, [&](const LcdNode& na, const LcdNode& nb) {
    const Box3f around = box_around(nb, box_of);  // rows whose box misses it hold no pair (block_pairs)
    for (std::uint32_t x = na.first; x < na.first + na.count; ++x) {
      if (!boxes_meet(box_of(x), around, it.offset)) continue;
      for (std::uint32_t y = nb.first; y < nb.first + nb.count; ++y) test(x, y);
    }
  });
}

__global__ void count_pairs_kernel(StandView v, const std::uint64_t* keys, std::uint32_t n, Counters* c) {
  const std::uint32_t k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= n) return;
  const bool within = v.organs[key_hi(keys[k])].plant == v.organs[key_lo(keys[k])].plant;
  atomicAdd(within ? &c->within : &c->between, 1ull);
}

__global__ void cluster_keys_kernel(const ClusterPair* pairs, std::uint32_t n, std::uint64_t* keys,
                                    std::uint32_t* work) {
  const std::uint32_t k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= n) return;
  keys[k] = pair_key(pairs[k].a, pairs[k].b);
  work[k] = pairs[k].work;
}

__global__ void cluster_pairs_from_keys_kernel(const std::uint64_t* keys, const std::uint32_t* work,
                                               std::uint32_t n, ClusterPair* out) {
  const std::uint32_t k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k < n) out[k] = ClusterPair{work[k], key_hi(keys[k]), key_lo(keys[k])};
}

__global__ void cluster_contacts_kernel(const WorkItem* work, const std::uint32_t* work_of,
                                        const std::uint64_t* keys, std::uint32_t n, Contact* out) {
  const std::uint32_t k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= n) return;
  const WorkItem w = work[work_of[k]];
  out[k] = Contact{-1,
                   -1,
                   w.p,
                   w.q,
                   static_cast<std::int32_t>(key_hi(keys[k])),
                   static_cast<std::int32_t>(key_lo(keys[k]))};
}

__global__ void contacts_kernel(StandView v, const std::uint64_t* keys, std::uint32_t n, Contact* out) {
  const std::uint32_t k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= n) return;
  const auto a = static_cast<std::int32_t>(key_hi(keys[k])), b = static_cast<std::int32_t>(key_lo(keys[k]));
  out[k] = Contact{a, b, v.organs[a].plant, v.organs[b].plant, -1, -1};
}

/// A warp per organ pair (cuda/organ_pair_test.cuh) at the stand's transforms.
__global__ void exact_kernel(StandView v, const std::uint64_t* keys, std::uint32_t n, float clearance,
                             std::uint8_t* hit) {
  __shared__ volatile int done[kThreads / 32];
  __shared__ WarpStage stage[kThreads / 32];
  const std::uint64_t t = static_cast<std::uint64_t>(blockIdx.x) * blockDim.x + threadIdx.x;
  const auto k = static_cast<std::uint32_t>(t / 32);
  if (k >= n) return;  // whole warps: n x 32 threads in blocks of whole warps
  const std::uint32_t a = key_hi(keys[k]), b = key_lo(keys[k]);
  const bool found = warp_organs_touch(v, a, v.transforms[a], b, v.transforms[b], clearance,
                                       done[threadIdx.x / 32], &stage[threadIdx.x / 32]);
  if (threadIdx.x % 32 == 0) hit[k] = found ? 1 : 0;
}

unsigned blocks(std::uint64_t n) { return static_cast<unsigned>((n + kThreads - 1) / kThreads); }

}  // namespace

void launch_work_items(const StandView& v, const std::uint64_t* keys, std::uint32_t n, WorkItem* out) {
  if (!n) return;
  work_items_kernel<<<blocks(n), kThreads>>>(v, keys, n, out);
  CANOPY_CUDA_CHECK_LAUNCH("work_items_kernel");
}

void launch_cluster_pairs(const StandView& v, const WorkItem* work, std::uint32_t n_work, ClusterPair* out,
                          unsigned long long capacity, Counters* counters) {
  if (!n_work) return;
  cluster_pairs_kernel<<<blocks(std::uint64_t{n_work} * kClusterLanes), kThreads>>>(v, work, n_work, out,
                                                                                    capacity, counters);
  CANOPY_CUDA_CHECK_LAUNCH("cluster_pairs_kernel");
}

void launch_organ_pairs(const StandView& v, const WorkItem* work, const ClusterPair* pairs,
                        std::uint32_t n_pairs, std::uint64_t* out, unsigned long long capacity,
                        Counters* counters) {
  if (!n_pairs) return;
  organ_pairs_kernel<<<blocks(n_pairs), kThreads>>>(v, work, pairs, n_pairs, out, capacity, counters);
  CANOPY_CUDA_CHECK_LAUNCH("organ_pairs_kernel");
}

void launch_count_pairs(const StandView& v, const std::uint64_t* keys, std::uint32_t n, Counters* counters) {
  if (!n) return;
  count_pairs_kernel<<<blocks(n), kThreads>>>(v, keys, n, counters);
  CANOPY_CUDA_CHECK_LAUNCH("count_pairs_kernel");
}

void launch_cluster_keys(const ClusterPair* pairs, std::uint32_t n, std::uint64_t* keys,
                         std::uint32_t* work) {
  if (!n) return;
  cluster_keys_kernel<<<blocks(n), kThreads>>>(pairs, n, keys, work);
  CANOPY_CUDA_CHECK_LAUNCH("cluster_keys_kernel");
}

void launch_cluster_pairs_from_keys(const std::uint64_t* keys, const std::uint32_t* work, std::uint32_t n,
                                    ClusterPair* out) {
  if (!n) return;
  cluster_pairs_from_keys_kernel<<<blocks(n), kThreads>>>(keys, work, n, out);
  CANOPY_CUDA_CHECK_LAUNCH("cluster_pairs_from_keys_kernel");
}

void launch_cluster_contacts(const WorkItem* work, const std::uint32_t* work_of, const std::uint64_t* keys,
                             std::uint32_t n, Contact* out) {
  if (!n) return;
  cluster_contacts_kernel<<<blocks(n), kThreads>>>(work, work_of, keys, n, out);
  CANOPY_CUDA_CHECK_LAUNCH("cluster_contacts_kernel");
}

void launch_contacts(const StandView& v, const std::uint64_t* keys, std::uint32_t n, Contact* out) {
  if (!n) return;
  contacts_kernel<<<blocks(n), kThreads>>>(v, keys, n, out);
  CANOPY_CUDA_CHECK_LAUNCH("contacts_kernel");
}

void launch_exact(const StandView& v, const std::uint64_t* keys, std::uint32_t n_pairs, float clearance,
                  std::uint8_t* hit) {
  if (!n_pairs) return;
  exact_kernel<<<blocks(std::uint64_t{n_pairs} * 32), kThreads>>>(v, keys, n_pairs, clearance, hit);
  CANOPY_CUDA_CHECK_LAUNCH("exact_kernel");
}

namespace {
__global__ void scatter_kernel(std::uint32_t* dst, const std::uint32_t* src, const std::uint32_t* index,
                               std::uint32_t n, std::uint32_t words) {
  const std::uint64_t k = static_cast<std::uint64_t>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (k >= static_cast<std::uint64_t>(n) * words) return;
  const std::uint64_t item = k / words, w = k % words;
  dst[static_cast<std::uint64_t>(index[item]) * words + w] = src[k];
}
}  // namespace

void launch_scatter(void* dst, const void* src, const std::uint32_t* index, std::uint32_t n,
                    std::uint32_t words) {
  const std::uint64_t total = static_cast<std::uint64_t>(n) * words;
  if (total == 0) return;
  scatter_kernel<<<static_cast<unsigned>((total + kThreads - 1) / kThreads), kThreads>>>(
      static_cast<std::uint32_t*>(dst), static_cast<const std::uint32_t*>(src), index, n, words);
  CANOPY_CUDA_CHECK_LAUNCH("scatter_kernel");
}

}  // namespace canopy::cuda
