#pragma once
/// The CUDA detection stages as launches over flat lists (no block per plant pair): cluster
/// pairs per plant pair, organ pairs per cluster pair, the exact test per organ pair. Kernels
/// take small views by value; the predicates are the shared CANOPY_HD ones.
#include "collision/mbvt.hpp"
#include "geometry/stand.hpp"

#include <cstdint>

namespace canopy::cuda {

struct MeshRef {
  std::uint32_t first_vertex = 0, vertex_count = 0, first_index = 0, triangle_count = 0;
};

struct StandView {
  const Affine3f* transforms;
  const OrganRecord* organs;
  const Obb* obbs;
  const std::uint32_t* cluster_organs;
  const Cluster* clusters;
  const LcdNode* nodes;
  const PlantBound* plants;
  const Vec3f* mesh_positions;
  const std::uint32_t* mesh_indices;
  const MeshRef* meshes;  // by prototype * (kMaxLod + 1) + lod
};

struct WorkItem {
  std::int32_t p, q;  // plants, p <= q
  Vec3f offset;       // q's origin minus p's, computed in double on the host
};

struct ClusterPair {
  std::uint32_t work, a, b;  // a <= b cluster indices
};

struct OrganPair {
  std::int32_t a, b;
  std::uint32_t work;
};

/// Counters the kernels add to: appended items (may exceed the capacity: then the caller grows
/// the buffer and runs again) and leaf-level counts between and within plants.
struct Counters {
  unsigned long long appended;
  unsigned long long between, within;
};

void launch_cluster_pairs(const StandView& v, const WorkItem* work, std::uint32_t n_work, ClusterPair* out,
                          unsigned long long capacity, Counters* counters);
void launch_organ_pairs(const StandView& v, const WorkItem* work, const ClusterPair* pairs, std::uint32_t n_pairs,
                        OrganPair* out, unsigned long long capacity, Counters* counters);
void launch_exact(const StandView& v, const WorkItem* work, const OrganPair* pairs, std::uint32_t n_pairs, float clearance,
                  std::uint8_t* hit);

/// dst[index[i]] = src[i] for i < n, items of `words` 32-bit words: moved organs' transforms and
/// boxes travel to the device one by one, not as whole arrays.
void launch_scatter(void* dst, const void* src, const std::uint32_t* index, std::uint32_t n, std::uint32_t words);

}  // namespace canopy::cuda
