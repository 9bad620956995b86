// stand.obj + stand.mtl, streamed organ by organ.
#include "geometry/export.hpp"
#include "geometry/organ_mesh.hpp"
#include "geometry/text_out.hpp"

#include <fmt/format.h>

namespace canopy {

void write_obj(const Stand& stand, PrototypeLibrary& lib, AtomicFile& obj, AtomicFile& mtl, const std::string& mtl_name) {
  std::string m = "# canopy: one material per organ kind\n";
  for (std::size_t k = 0; k < kOrganKindNames.size(); ++k) {
    const Vec3f c = kind_colour(static_cast<OrganKind>(k));
    m += fmt::format("newmtl {}\nKd {} {} {}\nKa 0 0 0\nKs 0 0 0\nd 1\nillum 1\n\n", kOrganKindNames[k], c.x, c.y, c.z);
  }
  mtl.write(m);

  std::string out;
  out.reserve(1 << 22);
  out += fmt::format("# canopy stand: {} plants, {} organs; metres, Z up, world coordinates\nmtllib {}\n",
                     stand.plant_count(), stand.organ_count(), mtl_name);
  std::size_t v_base = 1, vt_base = 1;
  OrganMesh mesh;
  for (std::size_t p = 0; p < stand.plant_count(); ++p) {
    const PlantRecord& pr = stand.plants[p];
    out += fmt::format("o plant_{}\n", p);
    for (std::size_t id = pr.first_organ; id < pr.first_organ + pr.organ_count; ++id) {
      organ_mesh(stand, id, lib, mesh);
      const PrototypeMesh& pm = *mesh.prototype;
      const bool uv = !pm.uvs.empty();
      out += fmt::format("g organ_{}\nusemtl {}\n", id, name_of(stand.organs[id].kind));
      for (const Vec3f& v : mesh.positions) {
        // Double sums keep micrometres 10^6 m from the origin; 7 decimals = 0.1 um.
        out += "v ";
        append_fixed(out, pr.x + static_cast<double>(v.x), 7);
        out += ' ';
        append_fixed(out, pr.y + static_cast<double>(v.y), 7);
        out += ' ';
        append_fixed(out, static_cast<double>(v.z), 7);
        out += '\n';
      }
      for (const Vec3f& n : mesh.normals) {
        out += "vn ";
        append_fixed(out, n.x, 6);
        out += ' ';
        append_fixed(out, n.y, 6);
        out += ' ';
        append_fixed(out, n.z, 6);
        out += '\n';
      }
      if (uv)
        for (const auto& t : pm.uvs) {
          out += "vt ";
          append_number(out, t[0]);
          out += ' ';
          append_number(out, t[1]);
          out += '\n';
        }
      for (std::size_t i = 0; i < pm.indices.size(); i += 3) {
        out += 'f';
        for (int k = 0; k < 3; ++k) {
          const std::size_t v = v_base + pm.indices[i + static_cast<std::size_t>(k)];
          out += ' ';
          append_number(out, v);
          out += '/';
          if (uv) append_number(out, vt_base + pm.indices[i + static_cast<std::size_t>(k)]);
          out += '/';
          append_number(out, v);
        }
        out += '\n';
      }
      v_base += pm.positions.size();
      if (uv) vt_base += pm.uvs.size();
      if (out.size() > (1u << 22) - 65536) {
        obj.write(out);
        out.clear();
      }
    }
  }
  obj.write(out);
}

}  // namespace canopy
