#include "collision/mbvt.hpp"
#include "collision/mbvt_fit.hpp"

#include <fmt/format.h>

#include <cmath>
#include <algorithm>
#include <stdexcept>

namespace canopy {
namespace {

void fit_cluster(Mbvt& m, const Cluster& c) { fit_cluster_nodes(m.nodes.data(), m.obbs.data(), m.cluster_organs.data(), c); }

/// The plant's bound, and its clusters' axis-aligned boxes on the way.
void fit_plant(Mbvt& m, PlantBound& pb) { fit_plant_bound(m.nodes.data(), m.clusters.data(), pb); }

}  // namespace

KindMask default_collide_kinds() {
  KindMask k{};
  for (OrganKind o : {OrganKind::leaflet, OrganKind::petiole, OrganKind::rachis, OrganKind::internode, OrganKind::peduncle})
    k[static_cast<std::size_t>(o)] = true;
  return k;
}

KindMask parse_collide_kinds(const std::string& list) {
  KindMask k{};
  if (list == "all") {
    k.fill(true);
    return k;
  }
  std::size_t i = 0;
  while (i <= list.size()) {
    std::size_t j = list.find(',', i);
    if (j == std::string::npos) j = list.size();
    const std::string name = list.substr(i, j - i);
    const auto kind = parse_organ_kind(name);
    if (!kind)
      throw std::invalid_argument(fmt::format(
          "--collide: unknown organ kind '{}' (expected internode, petiole, rachis, leaflet, peduncle, fruit, flower or all)", name));
    k[static_cast<std::size_t>(*kind)] = true;
    i = j + 1;
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
  std::vector<LcdNode> nodes;
};

PlantPart build_plant(const Stand& s, const Mbvt& m, std::size_t p) {
  PlantPart part;
  const PlantRecord& pr = s.plants[p];
  const MbvtConfig& config = m.config;
  // One group per compound leaf (in order of first organ), then the stem organs in runs.
  std::vector<std::int32_t> group_of_leaf(pr.leaf_count, -1);
  std::vector<std::vector<std::uint32_t>> groups;
  std::vector<std::int32_t> group_leaf;
  std::vector<std::uint32_t> stem;
  for (std::uint32_t id = pr.first_organ; id < pr.first_organ + pr.organ_count; ++id) {
    if (!m.takes_part[id]) continue;
    const std::int32_t leaf = s.organs[id].leaf;
    const std::int64_t local = static_cast<std::int64_t>(leaf) - pr.first_leaf;
    if (leaf < 0 || local < 0 || local >= static_cast<std::int64_t>(pr.leaf_count)) {
      stem.push_back(id);
      continue;
    }
    std::int32_t& g = group_of_leaf[static_cast<std::size_t>(local)];
    if (g < 0) {
      g = static_cast<std::int32_t>(groups.size());
      groups.emplace_back();
      group_leaf.push_back(leaf);
    }
    groups[static_cast<std::size_t>(g)].push_back(id);
  }
  const auto chunk = static_cast<std::size_t>(config.stem_cluster);
  for (std::size_t i = 0; i < stem.size(); i += chunk) {
    groups.emplace_back(stem.begin() + static_cast<std::ptrdiff_t>(i),
                        stem.begin() + static_cast<std::ptrdiff_t>(std::min(stem.size(), i + chunk)));
    group_leaf.push_back(-1);
  }
  for (std::size_t g = 0; g < groups.size(); ++g) {
    Cluster c;
    c.plant = static_cast<std::int32_t>(p);
    c.leaf = group_leaf[g];
    c.first = static_cast<std::uint32_t>(part.organs.size());
    c.count = static_cast<std::uint32_t>(groups[g].size());
    part.organs.insert(part.organs.end(), groups[g].begin(), groups[g].end());
    // Tree leaves over chunks in string order, then parents pairing neighbours level by level
    // (the axis comes with the boxes: fit_cluster_axis).
    c.first_node = static_cast<std::uint32_t>(part.nodes.size());
    std::vector<std::uint32_t> level;
    for (std::uint32_t k = 0; k < c.count; k += static_cast<std::uint32_t>(config.leaf_chunk)) {
      LcdNode node;
      node.first = c.first + k;
      node.count = std::min<std::uint32_t>(static_cast<std::uint32_t>(config.leaf_chunk), c.count - k);
      level.push_back(static_cast<std::uint32_t>(part.nodes.size()));
      part.nodes.push_back(node);
    }
    while (level.size() > 1) {
      std::vector<std::uint32_t> up;
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
      level = up;
    }
    c.root = level[0];
    c.node_count = static_cast<std::uint32_t>(part.nodes.size()) - c.first_node;
    part.clusters.push_back(c);
  }
  return part;
}

}  // namespace

Mbvt build_mbvt_topology(const Stand& s, const MbvtConfig& config) {
  Mbvt m;
  m.config = config;
  const std::size_t n = s.organ_count();
  m.takes_part.resize(n);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) m.takes_part[i] = config.collide[static_cast<std::size_t>(s.organs[i].kind)] ? 1 : 0;
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
  m.clusters.resize(c0[np]);
  m.cluster_organs.resize(o0[np]);
  m.nodes.resize(n0[np]);
  m.plants.resize(np);
#pragma omp parallel for schedule(dynamic, 16)
  for (std::size_t p = 0; p < np; ++p) {
    const PlantPart& part = parts[p];
    const auto oo = static_cast<std::uint32_t>(o0[p]), no = static_cast<std::uint32_t>(n0[p]);
    std::copy(part.organs.begin(), part.organs.end(), m.cluster_organs.begin() + static_cast<std::ptrdiff_t>(o0[p]));
    for (std::size_t k = 0; k < part.nodes.size(); ++k) {
      LcdNode node = part.nodes[k];
      node.first += oo;
      if (node.left >= 0) node.left += static_cast<std::int32_t>(no), node.right += static_cast<std::int32_t>(no);
      m.nodes[n0[p] + k] = node;
    }
    for (std::size_t k = 0; k < part.clusters.size(); ++k) {
      Cluster c = part.clusters[k];
      c.first += oo, c.first_node += no, c.root += no;
      m.clusters[c0[p] + k] = c;
    }
    PlantBound& pb = m.plants[p];
    pb.first_cluster = static_cast<std::uint32_t>(c0[p]);
    pb.cluster_count = static_cast<std::uint32_t>(part.clusters.size());
  }
  return m;
}

void fit_mbvt(Mbvt& m, const Stand& s, PrototypeLibrary& lib) {
  const std::size_t n = s.organ_count();
  m.obbs.resize(n);
  const PrototypeMesh* meshes[4][kMaxLod + 1] = {};
  for (const OrganRecord& r : s.organs) {
    const PrototypeMesh*& slot = meshes[static_cast<int>(r.prototype)][r.lod];
    if (!slot) slot = &lib.get(r.prototype, r.lod);
  }
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    const OrganRecord& r = s.organs[i];
    m.obbs[i] = make_obb(s.transforms[i], meshes[static_cast<int>(r.prototype)][r.lod]->box, m.config.clearance);
  }
  const std::size_t np = m.plants.size();
#pragma omp parallel for schedule(dynamic, 16)
  for (std::size_t p = 0; p < np; ++p) {
    PlantBound& pb = m.plants[p];
    for (std::uint32_t c = pb.first_cluster; c < pb.first_cluster + pb.cluster_count; ++c) {
      fit_cluster_axis(m.nodes.data(), m.obbs.data(), m.cluster_organs.data(), m.clusters[c]);
      fit_cluster(m, m.clusters[c]);
    }
    fit_plant(m, pb);
  }
  m.max_radius = 0;
  for (const PlantBound& pb : m.plants) m.max_radius = std::max(m.max_radius, pb.radius);
}

Mbvt build_mbvt(const Stand& s, PrototypeLibrary& lib, const MbvtConfig& config) {
  Mbvt m = build_mbvt_topology(s, config);
  fit_mbvt(m, s, lib);
  return m;
}

void refit_mbvt(Mbvt& m, const Stand& s, PrototypeLibrary& lib, const std::vector<std::uint32_t>& organs) {
  std::vector<std::uint8_t> plant_dirty(m.plants.size(), 0);
  for (std::uint32_t id : organs) {
    const OrganRecord& r = s.organs[id];
    m.obbs[id] = make_obb(s.transforms[id], lib.get(r.prototype, r.lod).box, m.config.clearance);
    plant_dirty[static_cast<std::size_t>(r.plant)] = 1;
  }
  for (std::size_t p = 0; p < m.plants.size(); ++p) {
    if (!plant_dirty[p]) continue;
    PlantBound& pb = m.plants[p];
    for (std::uint32_t c = pb.first_cluster; c < pb.first_cluster + pb.cluster_count; ++c) fit_cluster(m, m.clusters[c]);
    fit_plant(m, pb);
    m.max_radius = std::max(m.max_radius, pb.radius);
  }
}

}  // namespace canopy
