#pragma once
/// The CUDA detection stages as launches over flat lists (no block per plant pair): cluster
/// pairs per plant pair, organ pairs per cluster pair, the exact test per organ pair. Kernels
/// take small views by value; the predicates are the shared CANOPY_HD ones.
#include "collision/contacts.hpp"
#include "collision/mbvt.hpp"
#include "geometry/stand.hpp"

#include <cstdint>

namespace canopy::cuda {

struct MeshRef {
  std::uint32_t first_vertex = 0, vertex_count = 0, first_index = 0, triangle_count = 0;
};

/// A plant's origin, in double as the stand keeps it: offsets between plants are made from
/// these on the device exactly as the host makes them (plant_offset).
struct PlantOrigin {
  double x = 0, y = 0;
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
  const MeshRef* meshes;  // by mesh_slot(prototype, lod, shape)
  const PlantOrigin* origins;
};

struct WorkItem {
  std::int32_t p, q;  // plants, p <= q
  Vec3f offset;       // q's origin minus p's (double difference, rounded to float)
};

struct ClusterPair {
  std::uint32_t work, a, b;  // a <= b cluster indices
};

/// Counters the kernels add to: appended items (may exceed the capacity: then the caller grows
/// the buffer and runs again) and a level's counts between and within plants.
struct Counters {
  unsigned long long appended;
  unsigned long long between, within;
  unsigned long long witness_hits;   // resolution's bulk attempts: answered by a pair's witness
  unsigned long long exact_touches;  // and by a warp's full test that found a touch
};

/// Plant pairs (p < q) of a work list of plant-pair keys (pair_key(p, q)) made into work items.
void launch_work_items(const StandView& v, const std::uint64_t* keys, std::uint32_t n, WorkItem* out);
void launch_cluster_pairs(const StandView& v, const WorkItem* work, std::uint32_t n_work, ClusterPair* out,
                          unsigned long long capacity, Counters* counters);
/// Cluster pairs as keys pair_key(a, b) with their work items (batch-local).
void launch_cluster_keys(const ClusterPair* pairs, std::uint32_t n, std::uint64_t* keys, std::uint32_t* work);
/// Cluster pairs back from keys and their work items (after a sort).
void launch_cluster_pairs_from_keys(const std::uint64_t* keys, const std::uint32_t* work, std::uint32_t n,
                                    ClusterPair* out);
/// Leaf-level contact records (plants of the work item, the two clusters) of cluster-pair keys.
void launch_cluster_contacts(const WorkItem* work, const std::uint32_t* work_of, const std::uint64_t* keys,
                             std::uint32_t n, Contact* out);
/// Organ pairs as keys pair_key(a, b), a < b (repeats possible: sort and de-duplicate).
void launch_organ_pairs(const StandView& v, const WorkItem* work, const ClusterPair* pairs,
                        std::uint32_t n_pairs, std::uint64_t* out, unsigned long long capacity,
                        Counters* counters);
/// Counts organ-pair keys between and within plants.
void launch_count_pairs(const StandView& v, const std::uint64_t* keys, std::uint32_t n, Counters* counters);
/// The contact records of organ-pair keys (organ ids and their plants).
void launch_contacts(const StandView& v, const std::uint64_t* keys, std::uint32_t n, Contact* out);
/// hit[k] = whether organ pair keys[k] touches (within `clearance` when it is positive).
void launch_exact(const StandView& v, const std::uint64_t* keys, std::uint32_t n, float clearance,
                  std::uint8_t* hit);

/// dst[index[i]] = src[i] for i < n, items of `words` 32-bit words: moved organs' transforms and
/// boxes travel to the device one by one, not as whole arrays.
void launch_scatter(void* dst, const void* src, const std::uint32_t* index, std::uint32_t n,
                    std::uint32_t words);

}  // namespace canopy::cuda
