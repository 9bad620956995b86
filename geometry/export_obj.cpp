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

void write_obj(const Stand& stand, PrototypeLibrary& lib, AtomicFile& obj, AtomicFile& mtl, const std::string& mtl_name) {
  std::string m = "# canopy: one material per organ kind\n";
  for (std::size_t k = 0; k < kOrganKindNames.size(); ++k) {
    const Vec3f c = kind_colour(static_cast<OrganKind>(k));
    m += fmt::format("newmtl {}\nKd {} {} {}\nKa 0 0 0\nKs 0 0 0\nd 1\nillum 1\n\n", kOrganKindNames[k], c.x, c.y, c.z);
  }
  mtl.write(m);
  obj.write(fmt::format("# canopy stand: {} plants, {} organs; metres, Z up, world coordinates\nmtllib {}\n",
                        stand.plant_count(), stand.organ_count(), mtl_name));
  // OBJ indices are global: vertex and texture-coordinate offsets of each plant, by prefix sums.
  const std::size_t n = stand.plant_count();
  std::vector<std::size_t> v_base(n + 1, 1), vt_base(n + 1, 1);
  for (std::size_t p = 0; p < n; ++p) {
    std::size_t v = 0, vt = 0;
    const PlantRecord& pr = stand.plants[p];
    for (std::size_t id = pr.first_organ; id < pr.first_organ + pr.organ_count; ++id) {
      const PrototypeMesh& pm = lib.get(stand.organs[id].prototype, stand.organs[id].lod);
      v += pm.positions.size();
      vt += pm.uvs.size();
    }
    v_base[p + 1] = v_base[p] + v;
    vt_base[p + 1] = vt_base[p] + vt;
  }
  write_ordered(obj, n, 4, [&](std::size_t first, std::size_t last, std::string& out) {
    OrganMesh mesh;
    for (std::size_t p = first; p < last; ++p) {
      const PlantRecord& pr = stand.plants[p];
      std::size_t vb = v_base[p], tb = vt_base[p];
      out += "o plant_";
      append_number(out, p);
      out += '\n';
      for (std::size_t id = pr.first_organ; id < pr.first_organ + pr.organ_count; ++id) {
        organ_mesh(stand, id, lib, mesh);
        const PrototypeMesh& pm = *mesh.prototype;
        const bool uv = !pm.uvs.empty();
        out += "g organ_";
        append_number(out, id);
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
        for (std::size_t i = 0; i < pm.indices.size(); i += 3) {
          out += 'f';
          for (std::size_t k = 0; k < 3; ++k) {
            const std::size_t v = vb + pm.indices[i + k];
            out += ' ';
            append_number(out, v);
            out += '/';
            if (uv) append_number(out, tb + pm.indices[i + k]);
            out += '/';
            append_number(out, v);
          }
          out += '\n';
        }
        vb += pm.positions.size();
        tb += pm.uvs.size();
      }
    }
  });
}

}  // namespace canopy
