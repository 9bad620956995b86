// stand.obj + stand.mtl: plants formatted in parallel, written in order.
#include "geometry/export.hpp"
#include "geometry/organ_mesh.hpp"
#include "geometry/text_out.hpp"

#include <fmt/format.h>

namespace canopy {
namespace {

void put_xyz(std::string& out, const char* tag, double x, double y, double z, int decimals) {
  out += tag;
  append_fixed(out, x, decimals);
  out += ' ';
  append_fixed(out, y, decimals);
  out += ' ';
  append_fixed(out, z, decimals);
  out += '\n';
}

}  // namespace

void write_obj(const ExportScope& e, PrototypeLibrary& lib, ChunkWriter& obj, ChunkWriter& mtl,
               const std::string& mtl_name) {
  const Stand& stand = e.stand;
  std::string m = "# canopy: one material per organ kind\n";
  for (std::size_t k = 0; k < kOrganKindNames.size(); ++k) {
    const Vec3f c = kind_colour(static_cast<OrganKind>(k));
    m += fmt::format("newmtl {}\nKd {} {} {}\nKa 0 0 0\nKs 0 0 0\nd 1\nillum 1\n\n", kOrganKindNames[k], c.x,
                     c.y, c.z);
  }
  mtl.fixed(m);
  obj.fixed(fmt::format("# canopy stand: {} plants, {} organs; metres, Z up, world coordinates\nmtllib {}\n",
                        e.plants_total, e.organs_total, mtl_name));
  // OBJ indices are global: vertex and texture-coordinate offsets of each plant, by prefix sums.
  const std::size_t n = e.plants.size();
  std::vector<std::uint64_t> base(2 * n, 0), totals;
  for (std::size_t i = 0; i < n; ++i) {
    const PlantRecord& pr = stand.plants[e.plants[i]];
    for (std::size_t id = pr.first_organ; id < pr.first_organ + pr.organ_count; ++id) {
      const PrototypeMesh& pm = lib.get(stand.organs[id]);
      base[2 * i] += pm.positions.size();
      base[2 * i + 1] += pm.uvs.size();
    }
  }
  e.exclusive(base, 2, totals);
  obj.plants(n, 4, [&](std::size_t i, std::string& out) {
    OrganMesh mesh;
    const std::size_t p = e.plants[i];
    const PlantRecord& pr = stand.plants[p];
    std::size_t vb = 1 + base[2 * i], tb = 1 + base[2 * i + 1];
    out += "o plant_";
    append_number(out, e.plant(p));
    out += '\n';
    for (std::size_t id = pr.first_organ; id < pr.first_organ + pr.organ_count; ++id) {
      organ_mesh(stand, id, lib, mesh);
      const PrototypeMesh& pm = *mesh.prototype;
      const bool uv = !pm.uvs.empty();
      out += "g organ_";
      append_number(out, e.organ(static_cast<std::int64_t>(id)));
      out += "\nusemtl ";
      out += name_of(stand.organs[id].kind);
      out += '\n';
      // Double sums keep micrometres 10^6 m from the origin; 7 decimals = 0.1 um.
      for (const Vec3f& v : mesh.positions)
        put_xyz(out, "v ", pr.x + static_cast<double>(v.x), pr.y + static_cast<double>(v.y), v.z, 7);
      for (const Vec3f& nv : mesh.normals) put_xyz(out, "vn ", nv.x, nv.y, nv.z, 6);
      for (const auto& t : pm.uvs) {
        out += "vt ";
        append_number(out, t[0]);
        out += ' ';
        append_number(out, t[1]);
        out += '\n';
      }
      for (std::size_t i3 = 0; i3 < pm.indices.size(); i3 += 3) {
        out += 'f';
        for (std::size_t k = 0; k < 3; ++k) {
          const std::size_t v = vb + pm.indices[i3 + k];
          out += ' ';
          append_number(out, v);
          out += '/';
          if (uv) append_number(out, tb + pm.indices[i3 + k]);
          out += '/';
          append_number(out, v);
        }
        out += '\n';
      }
      vb += pm.positions.size();
      tb += pm.uvs.size();
    }
  });
}

void write_obj(const Stand& stand, PrototypeLibrary& lib, AtomicFile& obj, AtomicFile& mtl,
               const std::string& mtl_name) {
  ChunkFile o(obj), m(mtl);
  write_obj(ExportScope::whole(stand), lib, o, m, mtl_name);
}

}  // namespace canopy
