// stand.ply: binary little-endian, vertices relative to stand_origin; plants filled in parallel.
#include "geometry/export.hpp"
#include "geometry/organ_mesh.hpp"
#include "geometry/text_out.hpp"

#include <fmt/format.h>

#include <bit>
#include <cstring>

namespace canopy {

static_assert(std::endian::native == std::endian::little, "PLY export writes the host's little-endian values");

void write_ply(const Stand& stand, PrototypeLibrary& lib, AtomicFile& out) {
  const std::size_t n = stand.plant_count();
  std::vector<std::size_t> base(n + 1, 0);  // first vertex of each plant
  std::size_t nf = 0;
  for (std::size_t p = 0; p < n; ++p) {
    const PlantRecord& pr = stand.plants[p];
    std::size_t v = 0;
    for (std::size_t id = pr.first_organ; id < pr.first_organ + pr.organ_count; ++id) {
      const PrototypeMesh& pm = lib.get(stand.organs[id].prototype, stand.organs[id].lod);
      v += pm.positions.size();
      nf += pm.triangle_count();
    }
    base[p + 1] = base[p] + v;
  }
  if (base[n] > 0x7fffffffULL) throw std::runtime_error("stand.ply: more than 2^31 vertices; export fewer plants");
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
      base[n], nf);
  out.write(header);

  write_ordered(out, n, 8, [&](std::size_t first, std::size_t last, std::string& buf) {
    OrganMesh mesh;
    buf.resize(24 * (base[last] - base[first]));
    char* w = buf.data();
    for (std::size_t p = first; p < last; ++p) {
      const PlantRecord& pr = stand.plants[p];
      const Vec3d off = stand.offset(p);
      for (std::size_t id = pr.first_organ; id < pr.first_organ + pr.organ_count; ++id) {
        organ_mesh(stand, id, lib, mesh);
        for (std::size_t i = 0; i < mesh.positions.size(); ++i, w += 24) {
          const float v[6] = {static_cast<float>(off.x + mesh.positions[i].x),
                              static_cast<float>(off.y + mesh.positions[i].y), mesh.positions[i].z,
                              mesh.normals[i].x, mesh.normals[i].y, mesh.normals[i].z};
          std::memcpy(w, v, 24);
        }
      }
    }
  });
  write_ordered(out, n, 8, [&](std::size_t first, std::size_t last, std::string& buf) {
    std::size_t faces = 0;
    for (std::size_t id = stand.plants[first].first_organ; id < stand.plants[last - 1].first_organ + stand.plants[last - 1].organ_count; ++id)
      faces += lib.get(stand.organs[id].prototype, stand.organs[id].lod).triangle_count();
    buf.resize(21 * faces);
    char* w = buf.data();
    for (std::size_t p = first; p < last; ++p) {
      const PlantRecord& pr = stand.plants[p];
      auto v0 = static_cast<std::int32_t>(base[p]);
      for (std::size_t id = pr.first_organ; id < pr.first_organ + pr.organ_count; ++id) {
        const PrototypeMesh& pm = lib.get(stand.organs[id].prototype, stand.organs[id].lod);
        for (std::size_t i = 0; i < pm.indices.size(); i += 3, w += 21) {
          w[0] = 3;
          const std::int32_t f[5] = {v0 + static_cast<std::int32_t>(pm.indices[i]), v0 + static_cast<std::int32_t>(pm.indices[i + 1]),
                                     v0 + static_cast<std::int32_t>(pm.indices[i + 2]), static_cast<std::int32_t>(p),
                                     static_cast<std::int32_t>(id)};
          std::memcpy(w + 1, f, 20);
        }
        v0 += static_cast<std::int32_t>(pm.positions.size());
      }
    }
  });
}

}  // namespace canopy
