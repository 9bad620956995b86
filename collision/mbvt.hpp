#pragma once
/// The mixed bounding volume tree (Ding et al. 2019 §3.2): per organ an OBB (prototype box x
/// transform), per cluster a small bottom-up tree of LCD boxes over its organs in string order
/// (along the petiole), per plant a bound from its largest outward extent. Clusters are the
/// compound leaves, plus consecutive runs of the organs outside any compound leaf (stem
/// internodes, trusses, fruit), so those take part like any other organ. Bounds are in each
/// plant's frame (origin excluded); tests between plants add the origin difference.
#include "collision/contacts.hpp"
#include "collision/lanes/organ_lanes.hpp"
#include "geometry/lcd.hpp"
#include "geometry/first_touch.hpp"
#include "geometry/obb.hpp"
#include "geometry/prototype.hpp"
#include "geometry/stand.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace canopy {

/// Organ kinds that take part in detection: every kind by default, fruit and flowers included,
/// so that a resolved stand is penetration-free for every organ in its files; `--collide`
/// narrows them (docs/design.md "Organ kinds by role").
using KindMask = std::array<bool, 7>;
KindMask default_collide_kinds();
/// Parses "leaflet,fruit,..." (or "all"); throws std::invalid_argument naming a bad kind.
KindMask parse_collide_kinds(const std::string& list);

struct MbvtConfig {
  KindMask collide = default_collide_kinds();
  float clearance = 0;  // every bound is inflated by it
  int leaf_chunk = 4;   // organs per LCD tree leaf
  /// Organs per cluster outside compound leaves: the most that still make one block of the pass
  /// (kBlockOrgans, collision/lcd_descent.hpp). Faster than 8 in bench_detect (half as many stem
  /// clusters, so fewer cluster pairs for a few more own pairs), 20 and more slower (they
  /// descend).
  int stem_cluster = 16;
};

struct LcdNode {
  Lcd box;
  std::int32_t left = -1, right = -1;  // children (node indices), -1 at a leaf of the tree
  std::uint32_t first = 0, count = 0;  // organs (in cluster_organs) under this node
};

struct Cluster {
  std::int32_t plant = 0;
  std::int32_t leaf = -1;              // compound leaf id, -1 for a stem cluster
  std::uint32_t first = 0, count = 0;  // organs in cluster_organs
  std::uint32_t root = 0;              // root node
  std::uint32_t first_node = 0, node_count = 0;
  Box3f box;  // axis-aligned, around the root's LCD box (lcd_aabb): a pre-test
};

struct PlantBound {
  float radius = 0;         // horizontal, around the plant origin
  float zlo = 0, zhi = -1;  // empty when zlo > zhi
  std::uint32_t first_cluster = 0, cluster_count = 0;
  Box3f box;  // axis-aligned, around its clusters' boxes (plant frame)
};

struct Mbvt {
  MbvtConfig config;
  FirstTouchVector<Obb> obbs;  // per organ (of every organ; unused where not taking part)
  /// The shape's arrays are written in full by its parallel loops: made unzeroed, their pages
  /// first touched by those loops (geometry/first_touch.hpp).
  UnzeroedVector<std::uint8_t> takes_part;       // per organ
  UnzeroedVector<std::int32_t> parent_of;        // per organ: its record's parent (the pass's adjacency test)
  UnzeroedVector<std::uint32_t> cluster_organs;  // organ ids, cluster by cluster
  /// Beside cluster_organs: each organ's later organs in its cluster that are not adjacent to
  /// it (free_pair_masks), and per cluster whether it holds such a pair; the host's (the CPU
  /// pass's own pairs), made with the shape.
  UnzeroedVector<std::uint64_t> free_after;
  UnzeroedVector<std::uint8_t> cluster_has_free;
  /// Per plant: whether its organs taking part hold a pair that is not adjacent, so it meets
  /// itself at the plant level (made with the shape; plants_with_free_pairs reads it).
  std::vector<std::uint8_t> plant_has_free;
  UnzeroedVector<Cluster> clusters;  // plant by plant
  UnzeroedVector<LcdNode> nodes;
  std::vector<PlantBound> plants;
  float max_radius = 0;
  OrganLanes lanes;  // the organs' axis-aligned boxes in lanes: the host's (fit_mbvt, refit_mbvt)
};

/// Builds the tree from the stand (never from meshes): its shape, then its boxes.
Mbvt build_mbvt(const Stand& stand, PrototypeLibrary& lib, const MbvtConfig& config);
/// build_mbvt into an existing tree (of any stand), every box and index made anew: its arrays
/// keep their memory where it is large enough, so a backend that detects stand after stand of
/// one size (benchmarks, sweeps) pays the page faults of its arrays once, not at every build.
void rebuild_mbvt(Mbvt& m, const Stand& stand, PrototypeLibrary& lib, const MbvtConfig& config);
/// The tree's shape alone, which depends on the stand's structure and not on organ poses:
/// which organs take part, clusters, their organs and node topology, plants' cluster ranges
/// (boxes, axes and bounds left empty). The CUDA backend fits the boxes on the device.
Mbvt build_mbvt_topology(const Stand& stand, const MbvtConfig& config);
/// The boxes of a tree from its shape: every organ's OBB, every cluster's LCD axis (from its
/// first organ towards the mean of its organs) and node boxes, every plant's bound, and the
/// organs' axis-aligned boxes in lanes.
void fit_mbvt(Mbvt& m, const Stand& stand, PrototypeLibrary& lib);
/// After organs turned: new OBBs for `organs` (ids) and new boxes for their clusters and plants
/// (lanes included), with the tree's shape and axes kept: a transform per organ, not a rebuild.
/// `threads`: how many threads (0: all cores); nothing moved, nothing is done.
void refit_mbvt(Mbvt& m, const Stand& stand, PrototypeLibrary& lib, const std::vector<std::uint32_t>& organs,
                int threads = 0);

/// The organ pair (a, b) and the offset that carries b's plant frame into a's.
Vec3f plant_offset(const Stand& stand, std::int32_t plant_a, std::int32_t plant_b);

}  // namespace canopy
