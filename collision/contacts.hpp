#pragma once
/// Contacts (docs/design.md "Contact levels", "contacts.csv"): organ pairs at the organ and exact
/// levels; plant pairs and cluster (compound-leaf) pairs, with organ ids -1, at the plant and
/// leaf levels. Lists are sorted, so they are the same on every run, thread count and backend.
#include "collision/contact_level.hpp"
#include "geometry/chunked_output.hpp"
#include "geometry/hd.hpp"
#include "geometry/stand.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

namespace canopy {

struct Contact {
  std::int32_t organ_a = -1, organ_b = -1;
  std::int32_t plant_a = -1, plant_b = -1;
  std::int32_t cluster_a = -1, cluster_b = -1;  // leaf level: the clusters (compound leaves) met
  auto key() const { return std::tie(organ_a, organ_b, plant_a, plant_b, cluster_a, cluster_b); }
  bool operator<(const Contact& o) const { return key() < o.key(); }
  bool operator==(const Contact& o) const { return key() == o.key(); }
};

/// Pairs found at a level: between two plants and inside one plant.
struct LevelCount {
  std::size_t between = 0, within = 0;
  std::size_t total() const { return between + within; }
};

struct Contacts {
  ContactLevel level = ContactLevel::exact;
  std::vector<Contact> pairs;                       // at `level`, sorted
  std::array<std::optional<LevelCount>, 4> counts;  // every level up to `level`
  std::array<double, 4> seconds{};                  // time spent per level
  double build_s = 0;       // bounding volume build or refit (CUDA: the tree's shape on the host and the fit)
  double load_s = 0;        // CUDA: stand and tree shape uploaded (detect, not redetect)
  std::size_t batches = 1;  // CUDA: batches of plant pairs the stages ran in
  std::array<double, 4> device_seconds{};  // CUDA: kernel time per level from CUDA events
};

/// The numbers of `pairs` between and within plants.
inline LevelCount count_pairs(const std::vector<Contact>& pairs) {
  LevelCount n;
  for (const Contact& c : pairs) (c.plant_a == c.plant_b ? n.within : n.between)++;
  return n;
}

/// The pairs whose flag in `hit` is set, in order (the exact level out of the organ level).
inline std::vector<Contact> keep_hits(const std::vector<Contact>& pairs,
                                      const std::vector<std::uint8_t>& hit) {
  std::vector<Contact> out;
  for (std::size_t i = 0; i < pairs.size(); ++i)
    if (hit[i]) out.push_back(pairs[i]);
  return out;
}

/// adjacent() for two organs of one plant, ia and ib, from their parents alone.
CANOPY_HD inline bool parents_adjacent(std::int32_t parent_a, std::int32_t ia, std::int32_t parent_b,
                                       std::int32_t ib) {
  return parent_a == ib || parent_b == ia || parent_a == parent_b;
}

/// Organs joined in the structure tree (parent and child, or two children of one parent, roots
/// of one plant included) touch by construction and are never a contact (docs/design.md "Adjacency").
CANOPY_HD inline bool adjacent(const OrganRecord& a, std::int32_t ia, const OrganRecord& b, std::int32_t ib) {
  return a.plant == b.plant && parents_adjacent(a.parent, ia, b.parent, ib);
}

/// contacts.csv of a whole stand: header `organ_a,organ_b,plant_a,plant_b,level`, rows sorted.
/// contacts.csv's header (without its line end), as written and as canopy render reads it back.
inline constexpr std::string_view kContactsCsvHeader = "organ_a,organ_b,plant_a,plant_b,level";
void write_contacts_csv(const Stand& stand, const Contacts& c, AtomicFile& out);
/// contacts.csv over an ExportScope: the rows of the scope's plants (a row belongs to its first
/// plant), ids mapped to the whole stand's (the same bytes as for the whole stand).
void write_contacts_csv(const ExportScope& scope, const std::vector<Contact>& pairs, ContactLevel level,
                        ChunkWriter& out);

}  // namespace canopy
