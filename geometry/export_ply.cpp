// stand.ply: binary little-endian, vertices relative to stand_origin.
#include "geometry/export.hpp"
#include "geometry/organ_mesh.hpp"
#include "geometry/text_out.hpp"

#include <fmt/format.h>

#include <bit>
#include <cstring>

namespace canopy {

static_assert(std::endian::native == std::endian::little, "PLY export writes the host's little-endian floats");

void write_ply(const Stand& stand, PrototypeLibrary& lib, AtomicFile& out) {
  std::size_t nv = 0, nf = 0;
  for (const OrganRecord& r : stand.organs) {
    const PrototypeMesh& pm = lib.get(r.prototype, r.lod);
    nv += pm.positions.size();
    nf += pm.triangle_count();
  }
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
      nv, nf);
  out.write(header);

  OrganMesh mesh;
  std::vector<char> buf;
  buf.reserve(1 << 22);
  auto put = [&](const void* p, std::size_t n) {
    const char* c = static_cast<const char*>(p);
    buf.insert(buf.end(), c, c + n);
  };
  auto flush = [&] {
    out.write(buf.data(), buf.size());
    buf.clear();
  };
  for (std::size_t p = 0; p < stand.plant_count(); ++p) {
    const PlantRecord& pr = stand.plants[p];
    const Vec3d off = stand.offset(p);
    for (std::size_t id = pr.first_organ; id < pr.first_organ + pr.organ_count; ++id) {
      organ_mesh(stand, id, lib, mesh);
      for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        const float v[6] = {static_cast<float>(off.x + mesh.positions[i].x), static_cast<float>(off.y + mesh.positions[i].y),
                            mesh.positions[i].z, mesh.normals[i].x, mesh.normals[i].y, mesh.normals[i].z};
        put(v, sizeof v);
      }
      if (buf.size() > (1u << 22)) flush();
    }
  }
  std::int32_t base = 0;
  for (std::size_t p = 0; p < stand.plant_count(); ++p) {
    const PlantRecord& pr = stand.plants[p];
    for (std::size_t id = pr.first_organ; id < pr.first_organ + pr.organ_count; ++id) {
      const PrototypeMesh& pm = lib.get(stand.organs[id].prototype, stand.organs[id].lod);
      for (std::size_t i = 0; i < pm.indices.size(); i += 3) {
        const std::uint8_t three = 3;
        put(&three, 1);
        const std::int32_t f[5] = {base + static_cast<std::int32_t>(pm.indices[i]),
                                   base + static_cast<std::int32_t>(pm.indices[i + 1]),
                                   base + static_cast<std::int32_t>(pm.indices[i + 2]), static_cast<std::int32_t>(p),
                                   static_cast<std::int32_t>(id)};
        put(f, sizeof f);
      }
      base += static_cast<std::int32_t>(pm.positions.size());
      if (buf.size() > (1u << 22)) flush();
    }
  }
  flush();
}

}  // namespace canopy
