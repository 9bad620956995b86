#pragma once
/// The stand glb's document, shared by the plain and the compact writer: a root node at the stand
/// origin with one child node and mesh per plant, the JSON arrays streamed plant by plant with
/// global numbers, then the BIN chunk made plant by plant (docs/design.md "Export files").
#include "geometry/chunked_output.hpp"
#include "geometry/stand.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace canopy::glb {

inline constexpr std::size_t kKinds = 7;  // organ kinds, one material each

/// Bytes per index for a primitive of `vertices` vertices: UNSIGNED_SHORT while its largest
/// index stays below 65,535 (the value glTF keeps for primitive restart), else UNSIGNED_INT.
inline std::size_t index_size_for(std::size_t vertices) { return vertices <= 65535 ? 2 : 4; }

/// What a plant adds to the document; the sums over the plants before it number its entries.
struct PlantCounts {
  std::uint64_t views = 0, accessors = 0, meshes = 0, bytes = 0;
  std::array<bool, kKinds> kinds{};
};

/// Where a plant's entries start: views, accessors and meshes of the plants before it (every
/// process's) and the offset of its block in the BIN chunk.
struct Before {
  std::uint64_t views = 0, accessors = 0, meshes = 0, offset = 0;
};

/// A plant's entries in the JSON arrays, each with the comma that separates it from the one before.
struct PlantJson {
  std::string child, node, mesh, accessors, views;
};

/// The writer's part of the document.
struct Document {
  std::string head;  // members after "asset", with their leading comma (extensions used)
  std::string tail;  // members after "buffers", with their leading comma (extras)
  /// The i-th written plant's JSON from its numbers and the material of each kind (-1: none).
  std::function<PlantJson(std::size_t i, const Before&, const std::array<int, kKinds>& material_of)> json;
  /// Fills the i-th written plant's BIN block (its counts' `bytes`, zeroed) at `at`.
  std::function<void(std::size_t i, char* at)> fill;
};

/// Writes the GLB: header, JSON chunk (patched with its length once known), BIN chunk.
void write_document(const ExportScope& e, ChunkWriter& out, const std::vector<PlantCounts>& counts,
                    const Document& doc);

/// A plant's organs grouped into primitives in kind order, leaflet blades (which carry UVs) apart
/// from the other organs of their kind; `Primitive` is built from {kind, uv, {}} and has `organs`.
template <class Primitive>
std::vector<Primitive> group_primitives(const Stand& s, std::size_t p) {
  std::vector<Primitive> prims;
  const PlantRecord& pr = s.plants[p];
  for (std::size_t id = pr.first_organ; id < pr.first_organ + pr.organ_count; ++id) {
    const OrganRecord& r = s.organs[id];
    const bool uv = r.prototype == PrototypeKind::leaflet;
    auto it = std::find_if(prims.begin(), prims.end(),
                           [&](const Primitive& q) { return q.kind == r.kind && q.uv == uv; });
    if (it == prims.end()) {
      prims.push_back({r.kind, uv, {}});
      it = prims.end() - 1;
    }
    it->organs.push_back(static_cast<std::uint32_t>(id));
  }
  std::stable_sort(prims.begin(), prims.end(), [](const Primitive& a, const Primitive& b) {
    return std::make_pair(a.kind, a.uv) < std::make_pair(b.kind, b.uv);
  });
  return prims;
}

}  // namespace canopy::glb
