// stand.glb with shared prototype meshes (EXT_mesh_gpu_instancing): one mesh per prototype,
// level of detail and organ kind, drawn once per organ with its translation, rotation and scale
// and its id as the per-instance `_ORGAN` attribute. Much smaller than the baked file; for
// engines that read the extension.
#include "geometry/export.hpp"
#include "geometry/glb_container.hpp"
#include "geometry/organ_mesh.hpp"
#include "geometry/text_out.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <tuple>

namespace canopy {
namespace {

/// Translation, rotation (unit quaternion x, y, z, w) and scale of an organ transform, whose
/// linear part is an orthonormal frame times a diagonal scale. Zero columns (zero-length or
/// zero-width organs) are completed from the others.
struct Trs {
  float t[3], q[4], s[3];
};

Trs decompose(const Affine3f& m) {
  Trs r{};
  r.t[0] = m.t.x, r.t[1] = m.t.y, r.t[2] = m.t.z;
  Vec3d c[3] = {to_double(m.c0), to_double(m.c1), to_double(m.c2)};
  double s[3];
  for (int k = 0; k < 3; ++k) s[k] = length(c[k]);
  // Complete degenerate columns to a right-handed orthonormal frame.
  Vec3d e[3];
  for (int k = 0; k < 3; ++k) e[k] = s[k] > 0 ? c[k] * (1 / s[k]) : Vec3d{0, 0, 0};
  for (int k = 0; k < 3; ++k) {
    if (s[k] > 0) continue;
    const Vec3d a = e[(k + 1) % 3], b = e[(k + 2) % 3];
    Vec3d v = cross(a, b);
    if (length(v) < 0.5) {  // two columns missing: any frame around the one that is left
      const Vec3d known = length(a) > 0.5 ? a : length(b) > 0.5 ? b : Vec3d{1, 0, 0};
      const Vec3d helper = std::fabs(known.z) < 0.9 ? Vec3d{0, 0, 1} : Vec3d{1, 0, 0};
      v = normalized(cross(known, helper));
    }
    e[k] = normalized(v);
  }
  // Rotation matrix with columns e0 e1 e2 to a quaternion (Shepperd's method).
  const double m00 = e[0].x, m10 = e[0].y, m20 = e[0].z, m01 = e[1].x, m11 = e[1].y, m21 = e[1].z,
               m02 = e[2].x, m12 = e[2].y, m22 = e[2].z;
  const double tr = m00 + m11 + m22;
  double x, y, z, w;
  if (tr > 0) {
    const double k = std::sqrt(tr + 1) * 2;
    w = 0.25 * k, x = (m21 - m12) / k, y = (m02 - m20) / k, z = (m10 - m01) / k;
  } else if (m00 > m11 && m00 > m22) {
    const double k = std::sqrt(1 + m00 - m11 - m22) * 2;
    w = (m21 - m12) / k, x = 0.25 * k, y = (m01 + m10) / k, z = (m02 + m20) / k;
  } else if (m11 > m22) {
    const double k = std::sqrt(1 + m11 - m00 - m22) * 2;
    w = (m02 - m20) / k, x = (m01 + m10) / k, y = 0.25 * k, z = (m12 + m21) / k;
  } else {
    const double k = std::sqrt(1 + m22 - m00 - m11) * 2;
    w = (m10 - m01) / k, x = (m02 + m20) / k, y = (m12 + m21) / k, z = 0.25 * k;
  }
  const double n = std::sqrt(x * x + y * y + z * z + w * w);
  r.q[0] = static_cast<float>(x / n), r.q[1] = static_cast<float>(y / n), r.q[2] = static_cast<float>(z / n),
  r.q[3] = static_cast<float>(w / n);
  for (int k = 0; k < 3; ++k) r.s[k] = static_cast<float>(s[k]);
  return r;
}

void append(std::string& bin, const void* p, std::size_t n) { bin.append(static_cast<const char*>(p), n); }

}  // namespace

void write_glb_instanced(const Stand& s, PrototypeLibrary& lib, AtomicFile& out) {
  // Shared meshes: one per (prototype, lod, kind, leaflet shape) that occurs.
  const auto key_of = [](const OrganRecord& r) {
    return std::make_tuple(static_cast<int>(r.prototype), static_cast<int>(r.lod), static_cast<int>(r.kind),
                           static_cast<int>(r.shape));
  };
  std::map<std::tuple<int, int, int, int>, int> mesh_of;
  for (const OrganRecord& r : s.organs) mesh_of.emplace(key_of(r), 0);
  std::string bin, views, accessors, meshes, materials, nodes, children;
  std::array<int, 7> material_of{};
  material_of.fill(-1);
  int nmat = 0, nview = 0, nacc = 0, nmesh = 0;
  const auto sep = [](std::string& t) {
    if (!t.empty()) t += ',';
  };
  const auto view = [&](const void* data, std::size_t bytes, int stride, int target) {
    sep(views);
    views += fmt::format("{{\"buffer\":0,\"byteOffset\":{},\"byteLength\":{}", bin.size(), bytes);
    if (stride) views += fmt::format(",\"byteStride\":{}", stride);
    if (target) views += fmt::format(",\"target\":{}", target);
    views += '}';
    append(bin, data, bytes);
    return nview++;
  };
  const auto accessor = [&](int v, int comp, std::size_t count, const char* type,
                            const std::string& extra = {}) {
    sep(accessors);
    accessors += fmt::format("{{\"bufferView\":{},\"componentType\":{},\"count\":{},\"type\":\"{}\"{}}}", v,
                             comp, count, type, extra);
    return nacc++;
  };
  for (auto& [key, index] : mesh_of) {
    const auto [proto, lod, kind, shape] = key;
    const PrototypeMesh& pm =
        lib.get(static_cast<PrototypeKind>(proto), lod, static_cast<std::uint8_t>(shape));
    if (material_of[static_cast<std::size_t>(kind)] < 0) {
      material_of[static_cast<std::size_t>(kind)] = nmat++;
      sep(materials);
      materials += material_json(static_cast<OrganKind>(kind));
    }
    std::string bounds = ",\"min\":[";
    append_number(bounds, pm.box.lo.x), bounds += ',', append_number(bounds, pm.box.lo.y), bounds += ',';
    append_number(bounds, pm.box.lo.z), bounds += "],\"max\":[";
    append_number(bounds, pm.box.hi.x), bounds += ',', append_number(bounds, pm.box.hi.y), bounds += ',';
    append_number(bounds, pm.box.hi.z), bounds += ']';
    const int apos = accessor(view(pm.positions.data(), 12 * pm.positions.size(), 0, 34962), 5126,
                              pm.positions.size(), "VEC3", bounds);
    const int anrm =
        accessor(view(pm.normals.data(), 12 * pm.normals.size(), 0, 34962), 5126, pm.normals.size(), "VEC3");
    std::string attrs = fmt::format("\"POSITION\":{},\"NORMAL\":{}", apos, anrm);
    if (!pm.uvs.empty())
      attrs += fmt::format(",\"TEXCOORD_0\":{}", accessor(view(pm.uvs.data(), 8 * pm.uvs.size(), 0, 34962),
                                                          5126, pm.uvs.size(), "VEC2"));
    const int aidx =
        accessor(view(pm.indices.data(), 4 * pm.indices.size(), 0, 34963), 5125, pm.indices.size(), "SCALAR");
    sep(meshes);
    meshes += fmt::format(
        "{{\"name\":\"{}_{}_lod{}{}\",\"primitives\":[{{\"attributes\":{{{}}},\"indices\":{},\"material\":{},"
        "\"mode\":4}}]}}",
        kOrganKindNames[static_cast<std::size_t>(kind)], kPrototypeNames[static_cast<std::size_t>(proto)],
        lod, shape ? fmt::format("_shape{}", shape) : std::string(), attrs, aidx,
        material_of[static_cast<std::size_t>(kind)]);
    index = nmesh++;
  }
  // Plants: a node each, translated to its origin relative to stand_origin (Z up: the root turns
  // the whole stand to glTF's Y up), with one instanced child per shared mesh it uses.
  std::size_t next_node = 1 + s.plant_count();
  std::string plant_nodes, instance_nodes;
  for (std::size_t p = 0; p < s.plant_count(); ++p) {
    const PlantRecord& pr = s.plants[p];
    std::map<int, std::vector<std::uint32_t>> by_mesh;
    for (std::uint32_t id = pr.first_organ; id < pr.first_organ + pr.organ_count; ++id) {
      const OrganRecord& r = s.organs[id];
      by_mesh[mesh_of.at(key_of(r))].push_back(id);
    }
    std::string kids;
    for (const auto& [mesh, ids] : by_mesh) {
      std::vector<float> t, q, sc, organ;
      for (std::uint32_t id : ids) {
        const Trs trs = decompose(s.transforms[id]);
        t.insert(t.end(), trs.t, trs.t + 3);
        q.insert(q.end(), trs.q, trs.q + 4);
        sc.insert(sc.end(), trs.s, trs.s + 3);
        organ.push_back(static_cast<float>(id));
      }
      const std::size_t n = ids.size();
      const int at = accessor(view(t.data(), 4 * t.size(), 0, 0), 5126, n, "VEC3");
      const int aq = accessor(view(q.data(), 4 * q.size(), 0, 0), 5126, n, "VEC4");
      const int as = accessor(view(sc.data(), 4 * sc.size(), 0, 0), 5126, n, "VEC3");
      const int ao = accessor(view(organ.data(), 4 * organ.size(), 0, 0), 5126, n, "SCALAR");
      sep(instance_nodes);
      instance_nodes += fmt::format(
          "{{\"mesh\":{},\"extensions\":{{\"EXT_mesh_gpu_instancing\":{{\"attributes\":{{\"TRANSLATION\":{},"
          "\"ROTATION\":{},"
          "\"SCALE\":{},\"_ORGAN\":{}}}}}}}}}",
          mesh, at, aq, as, ao);
      sep(kids);
      kids += std::to_string(next_node++);
    }
    const Vec3d off = s.offset(p);
    std::string tr;
    append_number(tr, off.x), tr += ',', append_number(tr, off.y), tr += ',', append_number(tr, off.z);
    sep(plant_nodes);
    plant_nodes += fmt::format("{{\"name\":\"plant_{}\",\"translation\":[{}]{}}}", p, tr,
                               kids.empty() ? std::string() : ",\"children\":[" + kids + "]");
    sep(children);
    children += std::to_string(p + 1);
  }
  std::string origin;
  append_number(origin, s.stand_origin.x), origin += ',', append_number(origin, s.stand_origin.z),
      origin += ',';
  append_number(origin, -s.stand_origin.y);
  std::string text = fmt::format(
      "{{\"asset\":{{\"version\":\"2.0\",\"generator\":\"canopy\"}},\"extensionsUsed\":[\"EXT_mesh_gpu_"
      "instancing\"],"
      "\"extensionsRequired\":[\"EXT_mesh_gpu_instancing\"],\"scene\":0,\"scenes\":[{{\"nodes\":[0]}}],"
      "\"nodes\":[{{\"name\":\"stand\",\"translation\":[{}],\"rotation\":[-0.70710678118654757,0,0,0."
      "70710678118654757]"
      "{}}}{}{}{}{}]",
      origin, children.empty() ? std::string() : ",\"children\":[" + children + "]",
      plant_nodes.empty() ? "" : ",", plant_nodes, instance_nodes.empty() ? "" : ",", instance_nodes);
  if (nmesh > 0)
    text += fmt::format(
        ",\"meshes\":[{}],\"accessors\":[{}],\"bufferViews\":[{}],\"materials\":[{}],\"buffers\":[{{"
        "\"byteLength\":{}}}]",
        meshes, accessors, views, materials, bin.size());
  text += '}';
  while (bin.size() % 4) bin.push_back('\0');
  begin_glb(out, text, bin.size());
  out.write(bin);
}

}  // namespace canopy
