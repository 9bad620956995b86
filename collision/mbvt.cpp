#include "collision/mbvt.hpp"
#include "collision/free_pairs.hpp"
#include "collision/mbvt_fit.hpp"
#include "collision/lanes/obb_fit_lanes.hpp"
#include "geometry/organ_mesh.hpp"
#include "geometry/split_list.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <cmath>
#include <algorithm>
#include <atomic>
#include <stdexcept>

namespace canopy {
namespace {

void fit_cluster(Mbvt& m, const Cluster& c) {
  fit_cluster_nodes(m.nodes.data(), m.obbs.data(), m.cluster_organs.data(), c);
}

/// The plant's bound, and its clusters' axis-aligned boxes on the way.
void fit_plant(Mbvt& m, PlantBound& pb) { fit_plant_bound(m.nodes.data(), m.clusters.data(), pb); }

}  // namespace

KindMask default_collide_kinds() {
  KindMask k{};
  k.fill(true);
  return k;
}

KindMask parse_collide_kinds(const std::string& list) {
  KindMask k{};
  if (list == "all") {
    k.fill(true);
    return k;
  }
  for (const std::string& name : split_list(list)) {
    if (name == "all")
      throw std::invalid_argument(
          fmt::format("--collide: 'all' stands alone (every kind), not in a list of kinds ('{}')", list));
    const auto kind = parse_organ_kind(name);
    if (!kind)
      throw std::invalid_argument(
          fmt::format("--collide: unknown organ kind '{}' (expected internode, petiole, rachis, leaflet, "
                      "peduncle, fruit, flower or all)",
                      name));
    k[static_cast<std::size_t>(*kind)] = true;
  }
  return k;
}

Vec3f plant_offset(const Stand& s, std::int32_t a, std::int32_t b) {
  const PlantRecord& pa = s.plants[static_cast<std::size_t>(a)];
  const PlantRecord& pb = s.plants[static_cast<std::size_t>(b)];
  return origin_offset(pa.x, pa.y, pb.x, pb.y);
}

namespace {

/// One plant's clusters, organs and tree nodes, with indices local to the plant.
struct PlantPart {
  std::vector<Cluster> clusters;
  std::vector<std::uint32_t> organs;
  std::vector<std::uint64_t> free_after;  // beside organs
  std::vector<std::uint8_t> has_free;     // per cluster
  bool plant_has_free = false;            // a pair of the plant's organs taking part
  std::vector<LcdNode> nodes;
};

PlantPart build_plant(const Stand& s, const Mbvt& m, std::size_t p) {
  PlantPart part;
  const PlantRecord& pr = s.plants[p];
  const MbvtConfig& config = m.config;
  // One group per compound leaf (in order of first organ), then the stem organs in runs: each
  // organ's group found in one pass, the groups' organs placed by counting in a second (lists
  // kept per thread: a plant's build makes no allocation of its own beyond its result).
  thread_local std::vector<std::int32_t> group_of_leaf, group_of;
  thread_local std::vector<std::int32_t> group_leaf;
  thread_local std::vector<std::uint32_t> group_first, level, up;
  group_of_leaf.assign(pr.leaf_count, -1);
  group_of.assign(pr.organ_count, -1);
  group_leaf.clear();
  std::uint32_t stem = 0, leaf_groups = 0;
  for (std::uint32_t k = 0; k < pr.organ_count; ++k) {
    const std::uint32_t id = pr.first_organ + k;
    if (!m.takes_part[id]) continue;
    const std::int32_t leaf = s.organs[id].leaf;
    const std::int64_t local = static_cast<std::int64_t>(leaf) - pr.first_leaf;
    if (leaf < 0 || local < 0 || local >= static_cast<std::int64_t>(pr.leaf_count)) {
      group_of[k] = -2 - static_cast<std::int32_t>(stem++);  // stem organ number, resolved below
      continue;
    }
    std::int32_t& g = group_of_leaf[static_cast<std::size_t>(local)];
    if (g < 0) g = static_cast<std::int32_t>(leaf_groups++), group_leaf.push_back(leaf);
    group_of[k] = g;
  }
  const auto chunk = static_cast<std::uint32_t>(config.stem_cluster);
  const std::uint32_t groups = leaf_groups + (stem + chunk - 1) / chunk;
  for (std::uint32_t g = leaf_groups; g < groups; ++g) group_leaf.push_back(-1);
  group_first.assign(groups + 1, 0);
  for (std::uint32_t k = 0; k < pr.organ_count; ++k) {
    std::int32_t& g = group_of[k];
    if (g == -1) continue;
    if (g < -1) g = static_cast<std::int32_t>(leaf_groups + static_cast<std::uint32_t>(-2 - g) / chunk);
    ++group_first[static_cast<std::size_t>(g) + 1];
  }
  for (std::uint32_t g = 0; g < groups; ++g) group_first[g + 1] += group_first[g];
  part.organs.resize(group_first[groups]);
  for (std::uint32_t k = 0; k < pr.organ_count; ++k)
    if (group_of[k] >= 0)
      part.organs[group_first[static_cast<std::size_t>(group_of[k])]++] = pr.first_organ + k;
  for (std::uint32_t g = groups; g > 0; --g) group_first[g] = group_first[g - 1];
  group_first[0] = 0;
  part.clusters.reserve(groups);
  for (std::uint32_t g = 0; g < groups; ++g) {
    Cluster c;
    c.plant = static_cast<std::int32_t>(p);
    c.leaf = group_leaf[g];
    c.first = group_first[g];
    c.count = group_first[g + 1] - group_first[g];
    // Tree leaves over chunks in string order, then parents pairing neighbours level by level
    // (the axis comes with the boxes: fit_cluster_axis).
    c.first_node = static_cast<std::uint32_t>(part.nodes.size());
    level.clear();
    for (std::uint32_t k = 0; k < c.count; k += static_cast<std::uint32_t>(config.leaf_chunk)) {
      LcdNode node;
      node.first = c.first + k;
      node.count = std::min<std::uint32_t>(static_cast<std::uint32_t>(config.leaf_chunk), c.count - k);
      level.push_back(static_cast<std::uint32_t>(part.nodes.size()));
      part.nodes.push_back(node);
    }
    while (level.size() > 1) {
      up.clear();
      for (std::size_t i = 0; i < level.size(); i += 2) {
        if (i + 1 == level.size()) {
          up.push_back(level[i]);
          continue;
        }
        LcdNode node;
        node.left = static_cast<std::int32_t>(level[i]);
        node.right = static_cast<std::int32_t>(level[i + 1]);
        node.first = part.nodes[level[i]].first;
        node.count = part.nodes[level[i]].count + part.nodes[level[i + 1]].count;
        up.push_back(static_cast<std::uint32_t>(part.nodes.size()));
        part.nodes.push_back(node);
      }
      std::swap(level, up);
    }
    c.root = level[0];
    c.node_count = static_cast<std::uint32_t>(part.nodes.size()) - c.first_node;
    part.clusters.push_back(c);
  }
  // The clusters' free pairs, while the plant's organ records are at hand.
  part.free_after.resize(part.organs.size());
  part.has_free.resize(groups);
  for (std::uint32_t g = 0; g < groups; ++g) {
    const Cluster& c = part.clusters[g];
    part.has_free[g] =
        free_pair_masks(s.organs.data(), &part.organs[c.first], c.count, &part.free_after[c.first]) ? 1 : 0;
    part.plant_has_free = part.plant_has_free || part.has_free[g];
  }
  // Otherwise a free pair can only lie across clusters (the plant's organs taking part, as the
  // plant level asks).
  if (!part.plant_has_free)
    part.plant_has_free = organs_hold_free_pair(s.organs.data(), part.organs.data(), 0,
                                                static_cast<std::uint32_t>(part.organs.size()));
  return part;
}

}  // namespace

namespace {

/// build_mbvt_topology into `m`, whose arrays keep their memory where they are large enough.
void lay_out_topology(Mbvt& m, const Stand& s, const MbvtConfig& config) {
  m.config = config;
  m.max_radius = 0;
  const std::size_t n = s.organ_count();
  m.takes_part.resize(n);
  m.parent_of.resize(n);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    m.takes_part[i] = config.collide[static_cast<std::size_t>(s.organs[i].kind)] ? 1 : 0;
    m.parent_of[i] = s.organs[i].parent;
  }
  // Plants in parallel, then placed one after another (local indices moved to global ones).
  const std::size_t np = s.plant_count();
  std::vector<PlantPart> parts(np);
#pragma omp parallel for schedule(dynamic, 16)
  for (std::size_t p = 0; p < np; ++p) parts[p] = build_plant(s, m, p);
  std::vector<std::size_t> c0(np + 1, 0), o0(np + 1, 0), n0(np + 1, 0);
  for (std::size_t p = 0; p < np; ++p) {
    c0[p + 1] = c0[p] + parts[p].clusters.size();
    o0[p + 1] = o0[p] + parts[p].organs.size();
    n0[p + 1] = n0[p] + parts[p].nodes.size();
  }
  m.clusters.resize(c0[np]);  // each written in full below
  m.cluster_organs.resize(o0[np]);
  m.free_after.resize(o0[np]);
  m.cluster_has_free.resize(c0[np]);
  m.plant_has_free.resize(np);
  m.nodes.resize(n0[np]);
  m.plants.assign(np, PlantBound{});  // bounds empty until fit
#pragma omp parallel for schedule(dynamic, 16)
  for (std::size_t p = 0; p < np; ++p) {
    PlantPart& part = parts[p];
    const auto oo = static_cast<std::uint32_t>(o0[p]), no = static_cast<std::uint32_t>(n0[p]);
    std::copy(part.organs.begin(), part.organs.end(),
              m.cluster_organs.begin() + static_cast<std::ptrdiff_t>(o0[p]));
    std::copy(part.free_after.begin(), part.free_after.end(),
              m.free_after.begin() + static_cast<std::ptrdiff_t>(o0[p]));
    std::copy(part.has_free.begin(), part.has_free.end(),
              m.cluster_has_free.begin() + static_cast<std::ptrdiff_t>(c0[p]));
    for (std::size_t k = 0; k < part.nodes.size(); ++k) {
      LcdNode node = part.nodes[k];
      node.first += oo;
      if (node.left >= 0)
        node.left += static_cast<std::int32_t>(no), node.right += static_cast<std::int32_t>(no);
      m.nodes[n0[p] + k] = node;
    }
    for (std::size_t k = 0; k < part.clusters.size(); ++k) {
      Cluster c = part.clusters[k];
      c.first += oo, c.first_node += no, c.root += no;
      m.clusters[c0[p] + k] = c;
    }
    m.plant_has_free[p] = part.plant_has_free ? 1 : 0;
    PlantBound& pb = m.plants[p];
    pb.first_cluster = static_cast<std::uint32_t>(c0[p]);
    pb.cluster_count = static_cast<std::uint32_t>(part.clusters.size());
    parts[p] = {};  // let go here, on all threads (10,000 plants' lists freed on one took 7 ms)
  }
}

}  // namespace

Mbvt build_mbvt_topology(const Stand& s, const MbvtConfig& config) {
  Mbvt m;
  lay_out_topology(m, s, config);
  return m;
}

namespace {

/// The OBBs of `count` (1 to 8) organs, id_of(t) the t-th one's id, 8 at a time (make_obbs8:
/// make_obb's bits).
template <typename IdOf>
void fit_obbs8(Mbvt& m, const Stand& s, PrototypeLibrary& lib, IdOf&& id_of, int count) {
  const Affine3f* transform[8];
  const Box3f* local[8];
  Obb* out[8];
  for (int t = 0; t < count; ++t) {
    const std::size_t id = id_of(t);
    const OrganRecord& r = s.organs[id];
    transform[t] = &s.transforms[id];
    local[t] = &lib.get(r).box;
    out[t] = &m.obbs[id];
  }
  make_obbs8(transform, local, count, m.config.clearance, out);
}

}  // namespace

void fit_mbvt(Mbvt& m, const Stand& s, PrototypeLibrary& lib) {
  const std::size_t n = s.organ_count();
  // The meshes made before threads share the library (a level of detail out of range is
  // reported there, not thrown inside the parallel loop); the boxes written in full below on all
  // threads, which also fault the array's pages in (FirstTouchAllocator).
  make_meshes(s, lib);
  m.obbs.resize(n);
  // Where the plants' organs follow one another and cover the stand (a grown stand's do), each
  // plant's OBBs are made just before its clusters read them, while they are in the caches;
  // otherwise all OBBs first.
  const std::size_t np = m.plants.size();
  bool tiled = true;
  for (std::size_t p = 0, next = 0; tiled && p < np; next += s.plants[p].organ_count, ++p)
    tiled = s.plants[p].first_organ == next;
  tiled = tiled && (np == 0 ? n == 0 : s.plants[np - 1].first_organ + s.plants[np - 1].organ_count == n);
  const auto fit_range = [&](std::size_t from, std::size_t to) {
    for (std::size_t first = from; first < to; first += 8)
      fit_obbs8(
          m, s, lib, [first](int t) { return first + static_cast<std::size_t>(t); },
          static_cast<int>(std::min<std::size_t>(8, to - first)));
  };
  if (!tiled) {
    const std::ptrdiff_t chunks = static_cast<std::ptrdiff_t>((n + 1023) / 1024);
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t k = 0; k < chunks; ++k)
      fit_range(static_cast<std::size_t>(k) * 1024,
                std::min<std::size_t>(n, static_cast<std::size_t>(k + 1) * 1024));
  }
  lay_out_lanes(m.lanes, m);
#pragma omp parallel for schedule(dynamic, 16)
  for (std::size_t p = 0; p < np; ++p) {
    if (tiled) fit_range(s.plants[p].first_organ, s.plants[p].first_organ + s.plants[p].organ_count);
    PlantBound& pb = m.plants[p];
    for (std::uint32_t c = pb.first_cluster; c < pb.first_cluster + pb.cluster_count; ++c) {
      fit_cluster_axis(m.nodes.data(), m.obbs.data(), m.cluster_organs.data(), m.clusters[c]);
      fit_cluster(m, m.clusters[c]);
      fill_organ_lanes(m.lanes, m, c);
    }
    fit_plant(m, pb);
    fill_cluster_lanes(m.lanes, m, static_cast<std::uint32_t>(p));
  }
  m.max_radius = 0;
  for (const PlantBound& pb : m.plants) m.max_radius = std::max(m.max_radius, pb.radius);
}

Mbvt build_mbvt(const Stand& s, PrototypeLibrary& lib, const MbvtConfig& config) {
  Mbvt m;
  rebuild_mbvt(m, s, lib, config);
  return m;
}

void rebuild_mbvt(Mbvt& m, const Stand& s, PrototypeLibrary& lib, const MbvtConfig& config) {
  lay_out_topology(m, s, config);
  fit_mbvt(m, s, lib);
}

void refit_mbvt(Mbvt& m, const Stand& s, PrototypeLibrary& lib, const std::vector<std::uint32_t>& organs,
                int threads) {
  // The moved organs' boxes, then the plants that hold one, each on `threads` threads (all by
  // default: a resolution round moves organs in most plants of a stand). Their meshes were made
  // by build_mbvt with this library.
  if (m.lanes.organ_first.size() != m.clusters.size())
    throw std::logic_error(
        "refit_mbvt: the tree's boxes were never fit on the host (build_mbvt or fit_mbvt first)");
  // Nothing moved: no thread is started (an idle OpenMP worker would then spin beside a
  // detection asked to run on one thread).
  if (organs.empty()) return;
  if (threads <= 0) threads = omp_get_max_threads();
  std::vector<std::uint8_t> plant_dirty(m.plants.size(), 0);
  const std::size_t n = organs.size();
  const std::ptrdiff_t groups = static_cast<std::ptrdiff_t>((n + 7) / 8);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::ptrdiff_t g = 0; g < groups; ++g) {
    const auto first = static_cast<std::size_t>(g) * 8;
    const int count = static_cast<int>(std::min<std::size_t>(8, n - first));
    fit_obbs8(
        m, s, lib,
        [&organs, first](int t) {
          return static_cast<std::size_t>(organs[first + static_cast<std::size_t>(t)]);
        },
        count);
    for (int t = 0; t < count; ++t)
      std::atomic_ref<std::uint8_t>(
          plant_dirty[static_cast<std::size_t>(s.organs[organs[first + static_cast<std::size_t>(t)]].plant)])
          .store(1, std::memory_order_relaxed);
  }
  float radius = m.max_radius;  // grows with the plants refitted, as build_mbvt sets it
  const std::ptrdiff_t np = static_cast<std::ptrdiff_t>(m.plants.size());
#pragma omp parallel for schedule(dynamic, 16) reduction(max : radius) num_threads(threads)
  for (std::ptrdiff_t p = 0; p < np; ++p) {
    if (!plant_dirty[static_cast<std::size_t>(p)]) continue;
    PlantBound& pb = m.plants[static_cast<std::size_t>(p)];
    for (std::uint32_t c = pb.first_cluster; c < pb.first_cluster + pb.cluster_count; ++c) {
      fit_cluster(m, m.clusters[c]);
      fill_organ_lanes(m.lanes, m, c);
    }
    fit_plant(m, pb);
    fill_cluster_lanes(m.lanes, m, static_cast<std::uint32_t>(p));
    radius = std::max(radius, pb.radius);
  }
  m.max_radius = radius;
}

}  // namespace canopy
