// stand.ply: binary little-endian, vertices relative to stand_origin; plants filled in parallel.
#include "geometry/export.hpp"
#include "geometry/organ_mesh.hpp"
#include "geometry/text_out.hpp"

#include <fmt/format.h>

#include <bit>
#include <cstring>

namespace canopy {

static_assert(std::endian::native == std::endian::little,
              "PLY export writes the host's little-endian values");

void write_ply(const ExportScope& e, PrototypeLibrary& lib, ChunkWriter& out) {
  const Stand& stand = e.stand;
  const std::size_t n = e.plants.size();
  std::vector<std::uint64_t> base(2 * n, 0), totals;  // first vertex and first face of each plant
  for (std::size_t i = 0; i < n; ++i) {
    const PlantRecord& pr = stand.plants[e.plants[i]];
    for (std::size_t id = pr.first_organ; id < pr.first_organ + pr.organ_count; ++id) {
      const PrototypeMesh& pm = lib.get(stand.organs[id]);
      base[2 * i] += pm.positions.size();
      base[2 * i + 1] += pm.triangle_count();
    }
  }
  e.exclusive(base, 2, totals);
  if (totals[0] > 0x7fffffffULL)
    throw std::runtime_error("stand.ply: more than 2^31 vertices; export fewer plants");
  std::string header = "ply\nformat binary_little_endian 1.0\ncomment canopy stand\ncomment stand_origin ";
  append_number(header, stand.stand_origin.x);
  header += ' ';
  append_number(header, stand.stand_origin.y);
  header += ' ';
  append_number(header, stand.stand_origin.z);
  header += fmt::format(
      "\nelement vertex {}\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\n"
      "property float ny\nproperty float nz\nelement face {}\nproperty list uchar int vertex_indices\n"
      "property int plant\nproperty int organ\nend_header\n",
      totals[0], totals[1]);
  out.fixed(header);

  out.plants(n, 8, [&](std::size_t i, std::string& buf) {
    OrganMesh mesh;
    const std::size_t p = e.plants[i];
    const PlantRecord& pr = stand.plants[p];
    const Vec3d off = stand.offset(p);
    for (std::size_t id = pr.first_organ; id < pr.first_organ + pr.organ_count; ++id) {
      organ_mesh(stand, id, lib, mesh);
      std::size_t w = buf.size();
      buf.resize(w + 24 * mesh.positions.size());
      for (std::size_t v = 0; v < mesh.positions.size(); ++v, w += 24) {
        const float f[6] = {static_cast<float>(off.x + mesh.positions[v].x),
                            static_cast<float>(off.y + mesh.positions[v].y),
                            mesh.positions[v].z,
                            mesh.normals[v].x,
                            mesh.normals[v].y,
                            mesh.normals[v].z};
        std::memcpy(buf.data() + w, f, 24);
      }
    }
  });
  out.plants(n, 8, [&](std::size_t i, std::string& buf) {
    const std::size_t p = e.plants[i];
    const PlantRecord& pr = stand.plants[p];
    auto v0 = static_cast<std::int32_t>(base[2 * i]);
    const auto plant = static_cast<std::int32_t>(e.plant(p));
    for (std::size_t id = pr.first_organ; id < pr.first_organ + pr.organ_count; ++id) {
      const PrototypeMesh& pm = lib.get(stand.organs[id]);
      const auto organ = static_cast<std::int32_t>(e.organ(static_cast<std::int64_t>(id)));
      std::size_t w = buf.size();
      buf.resize(w + 21 * pm.triangle_count());
      for (std::size_t k = 0; k < pm.indices.size(); k += 3, w += 21) {
        buf[w] = 3;
        const std::int32_t f[5] = {v0 + static_cast<std::int32_t>(pm.indices[k]),
                                   v0 + static_cast<std::int32_t>(pm.indices[k + 1]),
                                   v0 + static_cast<std::int32_t>(pm.indices[k + 2]), plant, organ};
        std::memcpy(buf.data() + w + 1, f, 20);
      }
      v0 += static_cast<std::int32_t>(pm.positions.size());
    }
  });
}

void write_ply(const Stand& stand, PrototypeLibrary& lib, AtomicFile& out) {
  ChunkFile f(out);
  write_ply(ExportScope::whole(stand), lib, f);
}

}  // namespace canopy
