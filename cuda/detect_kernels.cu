// The CUDA detection kernels. Same contact semantics as collision/detect_cpu.cpp: the same
// LCD, OBB and triangle predicates (geometry/*.hpp, CANOPY_HD), compiled with --fmad=false.
#include "collision/contacts.hpp"
#include "collision/lcd_descent.hpp"
#include "collision/mbvt_fit.hpp"
#include "cuda/append.cuh"
#include "cuda/check.hpp"
#include "cuda/detect_kernels.hpp"
#include "cuda/keys.hpp"
#include "geometry/lcd.hpp"
#include "geometry/obb.hpp"
#include "geometry/triangle_test.hpp"

namespace canopy::cuda {
namespace {

constexpr int kThreads = 128;

__device__ Vec3f offset_between(const StandView& v, std::int32_t p, std::int32_t q) {
  if (p == q) return {0, 0, 0};
  const PlantOrigin a = v.origins[p], b = v.origins[q];
  return origin_offset(a.x, a.y, b.x, b.y);
}

__global__ void work_items_kernel(StandView v, const std::uint64_t* keys, std::uint32_t n, WorkItem* out) {
  const std::uint32_t k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= n) return;
  const auto p = static_cast<std::int32_t>(key_hi(keys[k])), q = static_cast<std::int32_t>(key_lo(keys[k]));
  out[k] = WorkItem{p, q, offset_between(v, p, q)};
}

/// Threads per plant pair in the cluster-pairs kernel. Measured on the H200 at 10,000 plants
/// (kernel time): 1 lane 0.85 ms, 4 lanes 0.60 ms, 8 lanes 0.66 ms, 16 lanes 0.81 ms, 32 lanes 1.09 ms.
constexpr int kClusterLanes = 4;

/// kClusterLanes threads per plant pair: lane l takes the clusters l, l + kClusterLanes, ... of
/// plant p against the clusters of plant q (the axis-aligned pre-tests leave most of them little
/// to do, so one thread per plant pair would leave the GPU idle behind the busiest).
__global__ void cluster_pairs_kernel(StandView v, const WorkItem* work, std::uint32_t n_work, ClusterPair* out,
                                     unsigned long long capacity, Counters* c) {
  const std::uint64_t t = static_cast<std::uint64_t>(blockIdx.x) * blockDim.x + threadIdx.x;
  const auto w = static_cast<std::uint32_t>(t / kClusterLanes), lane = static_cast<std::uint32_t>(t % kClusterLanes);
  if (w >= n_work) return;
  const WorkItem it = work[w];
  const PlantBound pa = v.plants[it.p], pb = v.plants[it.q];
  unsigned long long found = 0;
  for (std::uint32_t i = pa.first_cluster + lane; i < pa.first_cluster + pa.cluster_count; i += kClusterLanes) {
    const Cluster ca = v.clusters[i];
    if (it.p != it.q && !boxes_meet(ca.box, pb.box, it.offset)) continue;  // pre-tests as on the CPU
    for (std::uint32_t j = it.p == it.q ? i : pb.first_cluster; j < pb.first_cluster + pb.cluster_count; ++j) {
      const Cluster& cb = v.clusters[j];
      if (i != j && !boxes_meet(ca.box, cb.box, it.offset)) continue;
      const bool meet = i == j ? organs_hold_free_pair(v.organs, v.cluster_organs, ca.first, ca.count) : lcd_overlap(v.nodes[ca.root].box, v.nodes[cb.root].box, it.offset);
      if (!meet) continue;
      ++found;
      append(out, capacity, c, ClusterPair{w, i, j});
    }
  }
  if (found) atomicAdd(it.p == it.q ? &c->within : &c->between, found);
}

__device__ void organ_pair(const StandView& v, std::int32_t a, std::int32_t b, const WorkItem& it, std::uint64_t* out,
                           unsigned long long capacity, Counters* c) {
  if (adjacent(v.organs[a], a, v.organs[b], b)) return;
  if (!obb_overlap(v.obbs[a], v.obbs[b], it.offset)) return;
  append(out, capacity, c, pair_key(static_cast<std::uint32_t>(a < b ? a : b), static_cast<std::uint32_t>(a < b ? b : a)));
}

__global__ void organ_pairs_kernel(StandView v, const WorkItem* work, const ClusterPair* pairs, std::uint32_t n,
                                   std::uint64_t* out, unsigned long long capacity, Counters* c) {
  const std::uint32_t k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= n) return;
  const ClusterPair cp = pairs[k];
  const WorkItem it = work[cp.work];
  const Cluster ca = v.clusters[cp.a], cb = v.clusters[cp.b];
  if (cp.a == cp.b) {
    for (std::uint32_t x = ca.first; x < ca.first + ca.count; ++x)
      for (std::uint32_t y = x + 1; y < ca.first + ca.count; ++y)
        organ_pair(v, static_cast<std::int32_t>(v.cluster_organs[x]), static_cast<std::int32_t>(v.cluster_organs[y]), it, out, capacity, c);
    return;
  }
  descend_lcd_trees(v.nodes, v.cluster_organs, ca.root, cb.root, it.offset,
                    [&](std::int32_t a, std::int32_t b) { organ_pair(v, a, b, it, out, capacity, c); });
}

/// Vertex k of organ o, in the frame of the lower organ's plant (moved by `offset`), exactly as
/// the host computes it: apply(m, p) + d.
__device__ Vec3f vertex(const StandView& v, const MeshRef& m, const Affine3f& t, Vec3f offset, std::uint32_t k) {
  return apply(t, v.mesh_positions[m.first_vertex + k]) + offset;
}

__global__ void count_pairs_kernel(StandView v, const std::uint64_t* keys, std::uint32_t n, Counters* c) {
  const std::uint32_t k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= n) return;
  const bool within = v.organs[key_hi(keys[k])].plant == v.organs[key_lo(keys[k])].plant;
  atomicAdd(within ? &c->within : &c->between, 1ull);
}

__global__ void cluster_keys_kernel(const ClusterPair* pairs, std::uint32_t n, std::uint64_t* keys, std::uint32_t* work) {
  const std::uint32_t k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= n) return;
  keys[k] = pair_key(pairs[k].a, pairs[k].b);
  work[k] = pairs[k].work;
}

__global__ void cluster_pairs_from_keys_kernel(const std::uint64_t* keys, const std::uint32_t* work, std::uint32_t n, ClusterPair* out) {
  const std::uint32_t k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k < n) out[k] = ClusterPair{work[k], key_hi(keys[k]), key_lo(keys[k])};
}

__global__ void cluster_contacts_kernel(const WorkItem* work, const std::uint32_t* work_of, const std::uint64_t* keys, std::uint32_t n,
                                        Contact* out) {
  const std::uint32_t k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= n) return;
  const WorkItem w = work[work_of[k]];
  out[k] = Contact{-1, -1, w.p, w.q, static_cast<std::int32_t>(key_hi(keys[k])), static_cast<std::int32_t>(key_lo(keys[k]))};
}

__global__ void contacts_kernel(StandView v, const std::uint64_t* keys, std::uint32_t n, Contact* out) {
  const std::uint32_t k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= n) return;
  const auto a = static_cast<std::int32_t>(key_hi(keys[k])), b = static_cast<std::int32_t>(key_lo(keys[k]));
  out[k] = Contact{a, b, v.organs[a].plant, v.organs[b].plant, -1, -1};
}

constexpr unsigned kFullWarp = 0xffffffffu;

__device__ float warp_min(float x) {
  for (int o = 16; o > 0; o /= 2) x = min_f(x, __shfl_xor_sync(kFullWarp, x, o));
  return x;
}

__device__ float warp_max(float x) {
  for (int o = 16; o > 0; o /= 2) x = max_f(x, __shfl_xor_sync(kFullWarp, x, o));
  return x;
}

/// A warp per organ pair: the lanes share a's triangles (each lane its own against all of b's)
/// and stop together once any lane finds a touching pair, since the answer is an "any" (the
/// same answer as one thread walking every pair: min and max are exact in any order, and the
/// containment test's votes are the serial loop's conjunction and disjunction).
__global__ void exact_kernel(StandView v, const std::uint64_t* keys, std::uint32_t n, float clearance, std::uint8_t* hit) {
  __shared__ volatile int done[kThreads / 32];
  const std::uint64_t t = static_cast<std::uint64_t>(blockIdx.x) * blockDim.x + threadIdx.x;
  const auto k = static_cast<std::uint32_t>(t / 32);
  const unsigned lane = threadIdx.x % 32, warp = threadIdx.x / 32;
  if (k >= n) return;  // whole warps: n x 32 threads in blocks of whole warps
  const std::uint32_t a = key_hi(keys[k]), b = key_lo(keys[k]);
  const OrganRecord ra = v.organs[a], rb = v.organs[b];
  const MeshRef ma = v.meshes[static_cast<int>(ra.prototype) * (kMaxLod + 1) + ra.lod];
  const MeshRef mb = v.meshes[static_cast<int>(rb.prototype) * (kMaxLod + 1) + rb.lod];
  const Affine3f ta = v.transforms[a], tb = v.transforms[b];
  const Vec3f zero{0, 0, 0};
  const Vec3f db = offset_between(v, ra.plant, rb.plant);
  // b's box, widened by the clearance: only a's triangles inside it need the full test.
  float lo[3] = {3e38f, 3e38f, 3e38f}, hi[3] = {-3e38f, -3e38f, -3e38f};
  for (std::uint32_t i = lane; i < mb.vertex_count; i += 32) {
    const Vec3f p = vertex(v, mb, tb, db, i);
    lo[0] = min_f(lo[0], p.x), lo[1] = min_f(lo[1], p.y), lo[2] = min_f(lo[2], p.z);
    hi[0] = max_f(hi[0], p.x), hi[1] = max_f(hi[1], p.y), hi[2] = max_f(hi[2], p.z);
  }
  for (int d = 0; d < 3; ++d) lo[d] = warp_min(lo[d]), hi[d] = warp_max(hi[d]);
  if (lane == 0) done[warp] = 0;
  __syncwarp();
  const double c = clearance;
  for (std::uint32_t i0 = 0; i0 < ma.triangle_count; i0 += 32) {
    const std::uint32_t i = i0 + lane;
    if (i < ma.triangle_count) {
      Vec3f a3[3];
      for (int q = 0; q < 3; ++q) a3[q] = vertex(v, ma, ta, zero, v.mesh_indices[ma.first_index + 3 * i + q]);
      const float alo[3] = {min_f(a3[0].x, min_f(a3[1].x, a3[2].x)), min_f(a3[0].y, min_f(a3[1].y, a3[2].y)), min_f(a3[0].z, min_f(a3[1].z, a3[2].z))};
      const float ahi[3] = {max_f(a3[0].x, max_f(a3[1].x, a3[2].x)), max_f(a3[0].y, max_f(a3[1].y, a3[2].y)), max_f(a3[0].z, max_f(a3[1].z, a3[2].z))};
      bool near = true;
      for (int d = 0; d < 3; ++d) near = near && alo[d] - c <= hi[d] && ahi[d] + c >= lo[d];
      for (std::uint32_t j = 0; near && j < mb.triangle_count && !done[warp]; ++j) {
        Vec3f b3[3];
        for (int q = 0; q < 3; ++q) b3[q] = vertex(v, mb, tb, db, v.mesh_indices[mb.first_index + 3 * j + q]);
        bool box = true;
        for (int d = 0; d < 3; ++d) {
          const float bl = d == 0 ? min_f(b3[0].x, min_f(b3[1].x, b3[2].x)) : d == 1 ? min_f(b3[0].y, min_f(b3[1].y, b3[2].y)) : min_f(b3[0].z, min_f(b3[1].z, b3[2].z));
          const float bh = d == 0 ? max_f(b3[0].x, max_f(b3[1].x, b3[2].x)) : d == 1 ? max_f(b3[0].y, max_f(b3[1].y, b3[2].y)) : max_f(b3[0].z, max_f(b3[1].z, b3[2].z));
          box = box && bl <= ahi[d] + c && bh >= alo[d] - c;
        }
        if (box && (c > 0 ? triangles_within(a3, b3, c) : triangles_intersect(a3, b3))) done[warp] = 1;
      }
    }
    __syncwarp();
    if (done[warp]) break;  // the same value in every lane after the sync
  }
  bool found = done[warp];
  // Containment: a point of one organ inside the other's convex solid (faces made on the fly,
  // shared by the lanes): no face sees it outside, and one sees it strictly inside.
  const auto solid = [](PrototypeKind p) { return p == PrototypeKind::cylinder || p == PrototypeKind::sphere; };
  const auto inside = [&](Vec3f p, const MeshRef& m, const Affine3f& tr, Vec3f d) {
    bool outer = false, inner = false;
    for (std::uint32_t f = lane; f < m.triangle_count; f += 32) {
      const D3 x = d3(vertex(v, m, tr, d, v.mesh_indices[m.first_index + 3 * f]));
      const D3 y = d3(vertex(v, m, tr, d, v.mesh_indices[m.first_index + 3 * f + 1]));
      const D3 z = d3(vertex(v, m, tr, d, v.mesh_indices[m.first_index + 3 * f + 2]));
      const double o = orient3d(x, y, z, d3(p));
      outer = outer || o > 0;
      inner = inner || o < 0;
    }
    return !__any_sync(kFullWarp, outer) && __any_sync(kFullWarp, inner);
  };
  if (!found && solid(rb.prototype) && ma.vertex_count) found = inside(vertex(v, ma, ta, zero, 0), mb, tb, db);
  if (!found && solid(ra.prototype) && mb.vertex_count) found = inside(vertex(v, mb, tb, db, 0), ma, ta, zero);
  if (lane == 0) hit[k] = found ? 1 : 0;
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
  cluster_pairs_kernel<<<blocks(std::uint64_t{n_work} * kClusterLanes), kThreads>>>(v, work, n_work, out, capacity, counters);
  CANOPY_CUDA_CHECK_LAUNCH("cluster_pairs_kernel");
}

void launch_organ_pairs(const StandView& v, const WorkItem* work, const ClusterPair* pairs, std::uint32_t n_pairs,
                        std::uint64_t* out, unsigned long long capacity, Counters* counters) {
  if (!n_pairs) return;
  organ_pairs_kernel<<<blocks(n_pairs), kThreads>>>(v, work, pairs, n_pairs, out, capacity, counters);
  CANOPY_CUDA_CHECK_LAUNCH("organ_pairs_kernel");
}

void launch_count_pairs(const StandView& v, const std::uint64_t* keys, std::uint32_t n, Counters* counters) {
  if (!n) return;
  count_pairs_kernel<<<blocks(n), kThreads>>>(v, keys, n, counters);
  CANOPY_CUDA_CHECK_LAUNCH("count_pairs_kernel");
}

void launch_cluster_keys(const ClusterPair* pairs, std::uint32_t n, std::uint64_t* keys, std::uint32_t* work) {
  if (!n) return;
  cluster_keys_kernel<<<blocks(n), kThreads>>>(pairs, n, keys, work);
  CANOPY_CUDA_CHECK_LAUNCH("cluster_keys_kernel");
}

void launch_cluster_pairs_from_keys(const std::uint64_t* keys, const std::uint32_t* work, std::uint32_t n, ClusterPair* out) {
  if (!n) return;
  cluster_pairs_from_keys_kernel<<<blocks(n), kThreads>>>(keys, work, n, out);
  CANOPY_CUDA_CHECK_LAUNCH("cluster_pairs_from_keys_kernel");
}

void launch_cluster_contacts(const WorkItem* work, const std::uint32_t* work_of, const std::uint64_t* keys, std::uint32_t n,
                             Contact* out) {
  if (!n) return;
  cluster_contacts_kernel<<<blocks(n), kThreads>>>(work, work_of, keys, n, out);
  CANOPY_CUDA_CHECK_LAUNCH("cluster_contacts_kernel");
}

void launch_contacts(const StandView& v, const std::uint64_t* keys, std::uint32_t n, Contact* out) {
  if (!n) return;
  contacts_kernel<<<blocks(n), kThreads>>>(v, keys, n, out);
  CANOPY_CUDA_CHECK_LAUNCH("contacts_kernel");
}

void launch_exact(const StandView& v, const std::uint64_t* keys, std::uint32_t n_pairs, float clearance, std::uint8_t* hit) {
  if (!n_pairs) return;
  exact_kernel<<<blocks(std::uint64_t{n_pairs} * 32), kThreads>>>(v, keys, n_pairs, clearance, hit);
  CANOPY_CUDA_CHECK_LAUNCH("exact_kernel");
}

namespace {
__global__ void scatter_kernel(std::uint32_t* dst, const std::uint32_t* src, const std::uint32_t* index, std::uint32_t n,
                               std::uint32_t words) {
  const std::uint64_t k = static_cast<std::uint64_t>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (k >= static_cast<std::uint64_t>(n) * words) return;
  const std::uint64_t item = k / words, w = k % words;
  dst[static_cast<std::uint64_t>(index[item]) * words + w] = src[k];
}
}  // namespace

void launch_scatter(void* dst, const void* src, const std::uint32_t* index, std::uint32_t n, std::uint32_t words) {
  const std::uint64_t total = static_cast<std::uint64_t>(n) * words;
  if (total == 0) return;
  scatter_kernel<<<static_cast<unsigned>((total + kThreads - 1) / kThreads), kThreads>>>(
      static_cast<std::uint32_t*>(dst), static_cast<const std::uint32_t*>(src), index, n, words);
  CANOPY_CUDA_CHECK_LAUNCH("scatter_kernel");
}

}  // namespace canopy::cuda
