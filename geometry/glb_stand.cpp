// The stand glb's document: the JSON arrays are sections of per-plant chunks, numbered by
// exclusive sums over the plants before each (every process's, see ExportScope::exclusive), so a
// tiled run writes the same bytes as one process.
#include "geometry/glb_stand.hpp"

#include "geometry/glb_container.hpp"
#include "geometry/text_out.hpp"

#include <fmt/format.h>

namespace canopy::glb {

void write_document(const ExportScope& e, ChunkWriter& out, const std::vector<PlantCounts>& counts,
                    const Document& doc) {
  const Stand& s = e.stand;
  const std::size_t n = e.plants.size();
  constexpr int K = 4 + kKinds;  // views, accessors, meshes, bytes, then one flag per kind
  std::vector<std::uint64_t> before(K * n, 0), totals;
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t* b = &before[K * i];
    b[0] = counts[i].views, b[1] = counts[i].accessors, b[2] = counts[i].meshes, b[3] = counts[i].bytes;
    for (std::size_t k = 0; k < kKinds; ++k) b[4 + k] = counts[i].kinds[k] ? 1 : 0;
  }
  e.exclusive(before, K, totals);
  std::array<int, kKinds> material_of{};
  std::string materials;
  int nmat = 0;
  for (std::size_t k = 0; k < kKinds; ++k) {
    material_of[k] = totals[4 + k] ? nmat++ : -1;
    if (material_of[k] < 0) continue;
    if (nmat > 1) materials += ',';
    materials += material_json(static_cast<OrganKind>(k));
  }
  std::vector<PlantJson> json(n);
#pragma omp parallel for schedule(dynamic, 64)
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint64_t* b = &before[K * i];
    json[i] = doc.json(i, Before{b[0], b[1], b[2], b[3]}, material_of);
  }
  const auto section = [&](std::string PlantJson::*field) {
    out.plants(n, 256, [&](std::size_t i, std::string& t) { t += json[i].*field; });
  };

  // The JSON chunk, written directly (a document tree for a large stand costs more than the mesh);
  // the GLB header and the JSON chunk's length are patched in once its length is known.
  const std::uint64_t start = out.offset();
  out.fixed(std::string(20, '\0'));
  std::string origin;
  append_number(origin, s.stand_origin.x), origin += ',', append_number(origin, s.stand_origin.z);
  origin += ',', append_number(origin, -s.stand_origin.y);
  out.fixed(
      fmt::format("{{\"asset\":{{\"version\":\"2.0\",\"generator\":\"canopy\"}}{},\"scene\":0,\"scenes\":[{{"
                  "\"nodes\":[0]}}],"
                  "\"nodes\":[{{\"name\":\"stand\",\"translation\":[{}]{}",
                  doc.head, origin, e.plants_total ? ",\"children\":[" : ""));
  section(&PlantJson::child);
  out.fixed(e.plants_total ? "]}" : "}");  // glTF forbids an empty children list
  section(&PlantJson::node);
  out.fixed("]");
  const std::uint64_t bin_bytes = totals[3];
  if (totals[2] > 0) {
    out.fixed(",\"meshes\":[");
    section(&PlantJson::mesh);
    out.fixed("],\"accessors\":[");
    section(&PlantJson::accessors);
    out.fixed("],\"bufferViews\":[");
    section(&PlantJson::views);
    out.fixed(fmt::format("],\"materials\":[{}],\"buffers\":[{{\"byteLength\":{}}}]", materials, bin_bytes));
  }
  out.fixed(doc.tail + "}");
  std::uint64_t json_bytes = out.offset() - start - 20;
  if (json_bytes % 4) {
    out.fixed(std::string(4 - json_bytes % 4, ' '));
    json_bytes = out.offset() - start - 20;
  }
  out.patch(start, glb_header(json_bytes, bin_bytes));
  if (bin_bytes) {  // every block is a multiple of 4 bytes
    out.fixed(glb_bin_header(bin_bytes));
    out.plants(n, 1, [&](std::size_t i, std::string& buf) {
      // Made in place at the end of the chunk (no block of its own to copy); zeros are padding.
      const std::size_t at = buf.size();
      buf.resize(at + counts[i].bytes);
      doc.fill(i, buf.data() + at);
    });
  }
}

}  // namespace canopy::glb
