// stand.glb in compact form (KHR_mesh_quantization), streamed plant by plant like write_glb.
// Each plant node carries its translation (the corner of its box, Y up, relative to the stand
// origin) and a uniform scale, the position step; vertices are UNSIGNED_SHORT steps from that
// corner, normals normalized BYTEs, leaflet UVs normalized UNSIGNED_SHORTs, indices
// UNSIGNED_SHORT where a primitive has at most 65,535 vertices. The organ id is the node's
// extras.first_organ plus `_ORGAN`, an UNSIGNED_SHORT kept in the two bytes that pad each
// position to 4-byte alignment (a second bufferView over the same bytes), so ids cost nothing.
#include "geometry/export.hpp"
#include "geometry/glb_compact_layout.hpp"
#include "geometry/glb_stand.hpp"
#include "geometry/organ_mesh.hpp"
#include "geometry/text_out.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace canopy {
namespace {

using namespace glb_compact;

PlantLayout plan_plant(const Stand& s, std::size_t p, PrototypeLibrary& lib, double max_step) {
  PlantLayout L;
  L.prims = glb::group_primitives<Primitive>(s, p);
  const Vec3d off = s.offset(p);
  OrganMesh mesh;
  Vec3d lo{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
           std::numeric_limits<double>::max()};
  Vec3d hi{-lo.x, -lo.y, -lo.z};
  for (Primitive& q : L.prims) {
    for (std::uint32_t id : q.organs) {
      organ_mesh(s, id, lib, mesh, /*positions_only=*/true);
      for (const Vec3f& v : mesh.positions) {
        const Vec3d w = world(off, v);
        q.lo = {std::min(q.lo.x, w.x), std::min(q.lo.y, w.y), std::min(q.lo.z, w.z)};
        q.hi = {std::max(q.hi.x, w.x), std::max(q.hi.y, w.y), std::max(q.hi.z, w.z)};
      }
      q.vertices += mesh.positions.size();
      q.indices += mesh.prototype->indices.size();
    }
    lo = {std::min(lo.x, q.lo.x), std::min(lo.y, q.lo.y), std::min(lo.z, q.lo.z)};
    hi = {std::max(hi.x, q.hi.x), std::max(hi.y, q.hi.y), std::max(hi.z, q.hi.z)};
    L.vertices += q.vertices;
    if (q.uv) L.uv_vertices += q.vertices;
    L.index_bytes += q.index_bytes();
  }
  if (L.vertices == 0) return L;
  L.corner = lo;
  // The finest step, a float (so the node's scale reads back exactly), that spans the box.
  const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  float step = static_cast<float>(extent / kUnits);
  if (static_cast<double>(step) * kUnits < extent)
    step = std::nextafter(step, std::numeric_limits<float>::max());
  if (step <= 0) step = std::numeric_limits<float>::min();
  L.step = step <= max_step ? step : 0;
  return L;
}

/// The plant's binary block: positions with ids, normals, UVs, indices (each primitive in turn).
/// (L.bytes() at `out`, zeros where nothing is written: the padding.)
void fill_plant(const Stand& s, std::size_t p, const PlantLayout& L, PrototypeLibrary& lib, char* out) {
  char* pos = out;
  char* nrm = pos + L.pos_bytes();
  char* uvp = nrm + 4 * L.vertices;
  char* idx = uvp + 4 * L.uv_vertices;
  const Vec3d off = s.offset(p);
  const std::uint32_t first = s.plants[p].first_organ;
  OrganMesh mesh;
  for (const Primitive& q : L.prims) {
    std::uint32_t base = 0;
    char* const idx_start = idx;
    for (std::uint32_t id : q.organs) {
      organ_mesh(s, id, lib, mesh);
      const auto rel = static_cast<std::uint16_t>(id - first);
      const PrototypeMesh& pm = *mesh.prototype;
      for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        put_position(pos, world(off, mesh.positions[i]), L);
        std::memcpy(pos + L.id_offset(), &rel, 2), pos += L.stride();
        const Vec3f n = to_y_up(mesh.normals[i]);
        const std::int8_t c[4] = {snorm8(n.x), snorm8(n.y), snorm8(n.z), 0};
        std::memcpy(nrm, c, 4), nrm += 4;
        if (q.uv) {
          const std::uint16_t t[2] = {unorm16(pm.uvs[i][0]), unorm16(pm.uvs[i][1])};
          std::memcpy(uvp, t, 4), uvp += 4;
        }
      }
      for (std::uint32_t k : pm.indices) {
        const std::uint32_t v = base + k;
        if (q.index_size() == 2) {
          const auto h = static_cast<std::uint16_t>(v);
          std::memcpy(idx, &h, 2), idx += 2;
        } else {
          std::memcpy(idx, &v, 4), idx += 4;
        }
      }
      base += static_cast<std::uint32_t>(mesh.positions.size());
    }
    idx = idx_start + q.index_bytes();  // padding to 4 bytes stays zero
  }
}

void append_vec(std::string& out, double x, double y, double z) {
  append_number(out, x), out += ',', append_number(out, y), out += ',', append_number(out, z);
}

glb::PlantJson plant_json(std::int64_t plant, std::int64_t first_organ, const PlantLayout& L,
                          const glb::Before& before, const std::array<int, glb::kKinds>& material_of) {
  glb::PlantJson j;
  std::size_t nview = before.views, nacc = before.accessors, offset = before.offset;
  const std::size_t nmesh = before.meshes;
  j.child = fmt::format("{}{}", plant > 0 ? "," : "", plant + 1);
  if (L.prims.empty()) {
    j.node = fmt::format(",{{\"name\":\"plant_{}\"}}", plant);
    return j;
  }
  std::string place = ",\"translation\":[";
  append_vec(place, L.corner.x, L.corner.y, L.corner.z);
  place += ']';
  if (L.step > 0) place += ",\"scale\":[", append_vec(place, L.step, L.step, L.step), place += ']';
  j.node = fmt::format(",{{\"name\":\"plant_{}\",\"mesh\":{}{},\"extras\":{{\"first_organ\":{}}}}}", plant,
                       nmesh, place, first_organ);
  const auto view = [&](std::size_t at, std::size_t bytes, std::size_t stride, int target) {
    if (nview > 0) j.views += ',';
    j.views += fmt::format("{{\"buffer\":0,\"byteOffset\":{},\"byteLength\":{}", at, bytes);
    if (stride) j.views += fmt::format(",\"byteStride\":{}", stride);
    j.views += fmt::format(",\"target\":{}}}", target);
    return nview++;
  };
  const std::size_t vpos = view(offset, L.pos_bytes(), L.stride(), 34962);
  // The ids' view is as long as the positions' (its last bytes are the next view's first): readers
  // such as three.js take whole strides from a view.
  const std::size_t vid = view(offset + L.id_offset(), L.pos_bytes(), L.stride(), 34962);
  offset += L.pos_bytes();
  const std::size_t vnrm = view(offset, 4 * L.vertices, 4, 34962);
  offset += 4 * L.vertices;
  const std::size_t vuv = L.uv_vertices ? view(offset, 4 * L.uv_vertices, 4, 34962) : 0;
  offset += 4 * L.uv_vertices;
  const std::size_t vidx = view(offset, L.index_bytes, 0, 34963);
  std::size_t o_pos = 0, o_nrm = 0, o_uv = 0, o_idx = 0;
  std::string prims;
  for (const Primitive& q : L.prims) {
    const auto accessor = [&](std::size_t v, std::size_t off, int comp, bool normalized, std::size_t count,
                              const char* type, const std::string& extra = {}) {
      if (nacc > 0) j.accessors += ',';
      j.accessors += fmt::format(
          "{{\"bufferView\":{},\"byteOffset\":{},\"componentType\":{},{}\"count\":{},\"type\":\"{}\"{}}}", v,
          off, comp, normalized ? "\"normalized\":true," : "", count, type, extra);
      return nacc++;
    };
    std::string bounds = ",\"min\":[";
    if (L.step > 0) {
      const auto u = [&](double w, double c) { return static_cast<int>(units(w, c, L.step)); };
      bounds += fmt::format("{},{},{}],\"max\":[{},{},{}]", u(q.lo.x, L.corner.x), u(q.lo.y, L.corner.y),
                            u(q.lo.z, L.corner.z), u(q.hi.x, L.corner.x), u(q.hi.y, L.corner.y),
                            u(q.hi.z, L.corner.z));
    } else {
      const auto f = [](double w, double c) { return static_cast<double>(static_cast<float>(w - c)); };
      append_vec(bounds, f(q.lo.x, L.corner.x), f(q.lo.y, L.corner.y), f(q.lo.z, L.corner.z));
      bounds += "],\"max\":[";
      append_vec(bounds, f(q.hi.x, L.corner.x), f(q.hi.y, L.corner.y), f(q.hi.z, L.corner.z));
      bounds += ']';
    }
    const std::size_t apos =
        accessor(vpos, o_pos, L.step > 0 ? 5123 : 5126, false, q.vertices, "VEC3", bounds);
    const std::size_t anrm = accessor(vnrm, o_nrm, 5120, true, q.vertices, "VEC3");
    std::string attrs = fmt::format("\"POSITION\":{},\"NORMAL\":{}", apos, anrm);
    if (q.uv) attrs += fmt::format(",\"TEXCOORD_0\":{}", accessor(vuv, o_uv, 5123, true, q.vertices, "VEC2"));
    attrs += fmt::format(",\"_ORGAN\":{}", accessor(vid, o_pos, 5123, false, q.vertices, "SCALAR"));
    const std::size_t aidx =
        accessor(vidx, o_idx, q.index_size() == 2 ? 5123 : 5125, false, q.indices, "SCALAR");
    if (!prims.empty()) prims += ',';
    prims += fmt::format("{{\"attributes\":{{{}}},\"indices\":{},\"material\":{},\"mode\":4}}", attrs, aidx,
                         material_of[static_cast<std::size_t>(q.kind)]);
    o_pos += L.stride() * q.vertices;
    o_nrm += 4 * q.vertices;
    if (q.uv) o_uv += 4 * q.vertices;
    o_idx += q.index_bytes();
  }
  j.mesh = fmt::format("{}{{\"name\":\"plant_{}\",\"primitives\":[{}]}}", nmesh > 0 ? "," : "", plant, prims);
  return j;
}

}  // namespace

void check_glb_compact(const ExportScope& e) {
  for (std::uint32_t p : e.plants)
    if (e.stand.plants[p].organ_count > kCompactOrgansPerPlant)
      throw std::invalid_argument(
          fmt::format("--glb-compact: plant {} has {} organs; the compact glb numbers a plant's organs in 16 "
                      "bits (at most {}): "
                      "write the default glb",
                      e.plant(p), e.stand.plants[p].organ_count, kCompactOrgansPerPlant));
}

void write_glb_compact(const ExportScope& e, PrototypeLibrary& lib, ChunkWriter& out,
                       const GlbCompactConfig& config) {
  if (!(config.max_step > 0) || !std::isfinite(config.max_step))
    throw std::invalid_argument(
        fmt::format("compact glb: the largest position step must be a positive number of metres (got {})",
                    config.max_step));
  check_glb_compact(e);
  const Stand& s = e.stand;
  const std::size_t n = e.plants.size();
  std::vector<PlantLayout> plan(n);
  make_meshes(s, lib);
#pragma omp parallel for schedule(dynamic, 8)
  for (std::size_t i = 0; i < n; ++i) plan[i] = plan_plant(s, e.plants[i], lib, config.max_step);

  std::vector<glb::PlantCounts> counts(n);
  for (std::size_t i = 0; i < n; ++i) {
    const PlantLayout& L = plan[i];
    glb::PlantCounts& c = counts[i];
    if (!L.prims.empty()) c.views = 4 + (L.uv_vertices ? 1 : 0), c.meshes = 1, c.bytes = L.bytes();
    for (const Primitive& q : L.prims) {
      c.accessors += 4 + (q.uv ? 1 : 0);
      c.kinds[static_cast<std::size_t>(q.kind)] = true;
    }
  }
  glb::Document doc;
  doc.head =
      ",\"extensionsUsed\":[\"KHR_mesh_quantization\"],\"extensionsRequired\":[\"KHR_mesh_quantization\"]";
  doc.json = [&](std::size_t i, const glb::Before& before, const std::array<int, glb::kKinds>& material_of) {
    const std::size_t p = e.plants[i];
    const std::int64_t first = static_cast<std::int64_t>(s.plants[p].first_organ) + e.organ_shift[p];
    return plant_json(e.plant(p), first, plan[i], before, material_of);
  };
  doc.fill = [&](std::size_t i, char* at) { fill_plant(s, e.plants[i], plan[i], lib, at); };
  glb::write_document(e, out, counts, doc);
}

void write_glb_compact(const Stand& s, PrototypeLibrary& lib, AtomicFile& out,
                       const GlbCompactConfig& config) {
  ChunkFile f(out);
  write_glb_compact(ExportScope::whole(s), lib, f, config);
}

}  // namespace canopy
