// stand.glb: glTF 2.0 binary, streamed plant by plant. The JSON chunk comes first, so a first
// pass computes every count and POSITION bound; the second pass makes the same numbers again
// (same float operations) and writes them.
#include "geometry/export.hpp"
#include "geometry/glb_stand.hpp"
#include "geometry/organ_mesh.hpp"

#include "geometry/text_out.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>

namespace canopy {
namespace {

constexpr std::size_t kFloatIdLimit = std::size_t(1) << 24;  // FLOAT holds organ ids exactly below this

struct Primitive {
  OrganKind kind;
  bool uv;
  std::vector<std::uint32_t> organs;
  std::size_t vertices = 0, indices = 0;
  Vec3f lo{std::numeric_limits<float>::max(), std::numeric_limits<float>::max(),
           std::numeric_limits<float>::max()};
  Vec3f hi{-std::numeric_limits<float>::max(), -std::numeric_limits<float>::max(),
           -std::numeric_limits<float>::max()};
};

struct PlantLayout {
  std::vector<Primitive> prims;
  std::size_t pos_bytes = 0, uv_bytes = 0, id_bytes = 0, index_bytes = 0;
  /// Bytes per index, one size for the whole plant (glb::index_size_for its largest primitive):
  /// 2 for the default plant, 14 % fewer bytes in the default stand's glb (1,000 plants: 307 MB
  /// instead of 356). The block stays a multiple of 4 bytes, so the next plant's floats stay
  /// aligned.
  std::size_t index_size = 2;
  std::size_t bytes() const { return 2 * pos_bytes + uv_bytes + id_bytes + index_bytes; }
};

Vec3f glb_position(const Vec3d& off, Vec3f v) {
  return to_y_up(
      {static_cast<float>(off.x + v.x), static_cast<float>(off.y + v.y), static_cast<float>(off.z + v.z)});
}

PlantLayout plan_plant(const Stand& s, std::size_t p, PrototypeLibrary& lib, std::size_t id_size) {
  PlantLayout L;
  L.prims = glb::group_primitives<Primitive>(s, p);
  const Vec3d off = s.offset(p);
  OrganMesh mesh;
  for (Primitive& q : L.prims) {
    for (std::uint32_t id : q.organs) {
      organ_mesh(s, id, lib, mesh, /*positions_only=*/true);
      for (const Vec3f& v : mesh.positions) {
        const Vec3f w = glb_position(off, v);
        q.lo = {std::min(q.lo.x, w.x), std::min(q.lo.y, w.y), std::min(q.lo.z, w.z)};
        q.hi = {std::max(q.hi.x, w.x), std::max(q.hi.y, w.y), std::max(q.hi.z, w.z)};
      }
      q.vertices += mesh.positions.size();
      q.indices += mesh.prototype->indices.size();
    }
    L.pos_bytes += 12 * q.vertices;
    if (q.uv) L.uv_bytes += 8 * q.vertices;
    L.id_bytes += id_size * q.vertices;
    L.index_bytes += q.indices;
  }
  for (const Primitive& q : L.prims) L.index_size = std::max(L.index_size, glb::index_size_for(q.vertices));
  L.index_bytes = (L.index_size * L.index_bytes + 3) / 4 * 4;
  return L;
}

/// The plant's binary block (L.bytes() at `out`): positions, normals, UVs, organ ids, indices
/// (each primitive in turn).
void fill_plant(const Stand& s, std::size_t p, const PlantLayout& L, PrototypeLibrary& lib, bool float_ids,
                std::int64_t organ_shift, char* out) {
  char* pos = out;
  char* nrm = pos + L.pos_bytes;
  char* uvp = nrm + L.pos_bytes;
  char* ids = uvp + L.uv_bytes;
  char* idx = ids + L.id_bytes;
  const Vec3d off = s.offset(p);
  OrganMesh mesh;
  for (const Primitive& q : L.prims) {
    std::uint32_t base = 0;
    for (std::uint32_t id : q.organs) {
      organ_mesh(s, id, lib, mesh);
      const auto gid = static_cast<std::uint32_t>(id + organ_shift);
      const PrototypeMesh& pm = *mesh.prototype;
      for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        const Vec3f w = glb_position(off, mesh.positions[i]);
        const Vec3f n = to_y_up(mesh.normals[i]);
        std::memcpy(pos, &w, 12), pos += 12;
        std::memcpy(nrm, &n, 12), nrm += 12;
        if (q.uv) std::memcpy(uvp, pm.uvs[i].data(), 8), uvp += 8;
        if (float_ids) {
          const float f = static_cast<float>(gid);
          std::memcpy(ids, &f, 4), ids += 4;
        } else {
          const std::uint16_t h[2] = {static_cast<std::uint16_t>(gid & 0xffff),
                                      static_cast<std::uint16_t>(gid >> 16)};
          std::memcpy(ids, h, 4), ids += 4;
        }
      }
      const auto put = [&](auto index_type) {
        for (std::uint32_t k : pm.indices) {
          const auto v = static_cast<decltype(index_type)>(base + k);
          std::memcpy(idx, &v, sizeof v), idx += sizeof v;
        }
      };
      L.index_size == 2 ? put(std::uint16_t{}) : put(std::uint32_t{});
      base += static_cast<std::uint32_t>(mesh.positions.size());
    }
  }
  std::memset(idx, 0, static_cast<std::size_t>(out + L.bytes() - idx));  // the block's padding
}

/// A plant's entries in the JSON arrays, numbered after the plants before it (global order).
glb::PlantJson plant_json(std::int64_t plant, const PlantLayout& L, const glb::Before& before, bool float_ids,
                          const std::array<int, glb::kKinds>& material_of) {
  glb::PlantJson j;
  std::size_t nview = before.views, nacc = before.accessors, offset = before.offset;
  const std::size_t nmesh = before.meshes;
  j.child = fmt::format("{}{}", plant > 0 ? "," : "", plant + 1);
  if (L.prims.empty()) {  // a plant without organs: a node without a mesh
    j.node = fmt::format(",{{\"name\":\"plant_{}\"}}", plant);
    return j;
  }
  j.node = fmt::format(",{{\"name\":\"plant_{}\",\"mesh\":{}}}", plant, nmesh);
  const auto view = [&](std::size_t bytes, int stride, int target) {
    if (nview > 0) j.views += ',';
    j.views += fmt::format("{{\"buffer\":0,\"byteOffset\":{},\"byteLength\":{},\"target\":{}", offset, bytes,
                           target);
    if (stride) j.views += fmt::format(",\"byteStride\":{}", stride);
    j.views += '}';
    offset += bytes;
    return nview++;
  };
  const std::size_t vpos = view(L.pos_bytes, 12, 34962), vnrm = view(L.pos_bytes, 12, 34962);
  const std::size_t vuv = L.uv_bytes ? view(L.uv_bytes, 8, 34962) : 0;
  const std::size_t vid = view(L.id_bytes, 4, 34962), vidx = view(L.index_bytes, 0, 34963);
  std::size_t o_pos = 0, o_uv = 0, o_id = 0, o_idx = 0;
  std::string prims;
  for (const Primitive& q : L.prims) {
    const auto accessor = [&](std::size_t v, std::size_t off, int comp, std::size_t count, const char* type,
                              const std::string& extra = {}) {
      if (nacc > 0) j.accessors += ',';
      j.accessors += fmt::format(
          "{{\"bufferView\":{},\"byteOffset\":{},\"componentType\":{},\"count\":{},\"type\":\"{}\"{}}}", v,
          off, comp, count, type, extra);
      return nacc++;
    };
    std::string bounds = ",\"min\":[";
    append_number(bounds, q.lo.x), bounds += ',', append_number(bounds, q.lo.y), bounds += ',',
        append_number(bounds, q.lo.z);
    bounds += "],\"max\":[";
    append_number(bounds, q.hi.x), bounds += ',', append_number(bounds, q.hi.y), bounds += ',',
        append_number(bounds, q.hi.z);
    bounds += ']';
    const std::size_t apos = accessor(vpos, o_pos, 5126, q.vertices, "VEC3", bounds);
    const std::size_t anrm = accessor(vnrm, o_pos, 5126, q.vertices, "VEC3");
    std::string attrs = fmt::format("\"POSITION\":{},\"NORMAL\":{}", apos, anrm);
    if (q.uv) attrs += fmt::format(",\"TEXCOORD_0\":{}", accessor(vuv, o_uv, 5126, q.vertices, "VEC2"));
    attrs += fmt::format(",\"_ORGAN\":{}", float_ids ? accessor(vid, o_id, 5126, q.vertices, "SCALAR")
                                                     : accessor(vid, o_id, 5123, q.vertices, "VEC2"));
    const std::size_t aidx = accessor(vidx, o_idx, L.index_size == 2 ? 5123 : 5125, q.indices, "SCALAR");
    if (!prims.empty()) prims += ',';
    prims += fmt::format("{{\"attributes\":{{{}}},\"indices\":{},\"material\":{},\"mode\":4}}", attrs, aidx,
                         material_of[static_cast<std::size_t>(q.kind)]);
    o_pos += 12 * q.vertices;
    if (q.uv) o_uv += 8 * q.vertices;
    o_id += 4 * q.vertices;
    o_idx += L.index_size * q.indices;
  }
  j.mesh = fmt::format("{}{{\"name\":\"plant_{}\",\"primitives\":[{}]}}", nmesh > 0 ? "," : "", plant, prims);
  return j;
}

}  // namespace

void write_glb(const ExportScope& e, PrototypeLibrary& lib, ChunkWriter& out) {
  const Stand& s = e.stand;
  const bool float_ids = e.organs_total <= kFloatIdLimit;
  const std::size_t n = e.plants.size();
  std::vector<PlantLayout> plan(n);
  make_meshes(s, lib);
#pragma omp parallel for schedule(dynamic, 8)
  for (std::size_t i = 0; i < n; ++i) plan[i] = plan_plant(s, e.plants[i], lib, 4);
  std::vector<glb::PlantCounts> counts(n);
  for (std::size_t i = 0; i < n; ++i) {
    const PlantLayout& L = plan[i];
    glb::PlantCounts& c = counts[i];
    if (!L.prims.empty()) c.views = 4 + (L.uv_bytes ? 1 : 0), c.meshes = 1, c.bytes = L.bytes();
    for (const Primitive& q : L.prims) {
      c.accessors += 4 + (q.uv ? 1 : 0);
      c.kinds[static_cast<std::size_t>(q.kind)] = true;
    }
  }
  glb::Document doc;
  if (!float_ids)
    doc.tail =
        ",\"extras\":{\"_ORGAN\":\"VEC2 of UNSIGNED_SHORT: id = x + 65536 * y (more than 2^24 organs)\"}";
  doc.json = [&](std::size_t i, const glb::Before& before, const std::array<int, glb::kKinds>& material_of) {
    return plant_json(e.plant(e.plants[i]), plan[i], before, float_ids, material_of);
  };
  doc.fill = [&](std::size_t i, char* at) {
    fill_plant(s, e.plants[i], plan[i], lib, float_ids, e.organ_shift[e.plants[i]], at);
  };
  glb::write_document(e, out, counts, doc);
}

void check_glb_fits(const Stand& s, PrototypeLibrary& lib) {
  std::uint64_t bin = 0;
  for (const OrganRecord& r : s.organs) {
    const PrototypeMesh& m = lib.get(r);
    bin += 28 * static_cast<std::uint64_t>(m.positions.size()) +
           2 * static_cast<std::uint64_t>(m.indices.size());
  }
  if (bin > 0xffffffffULL)
    throw std::runtime_error(
        fmt::format("stand.glb would exceed 4 GiB, the GLB limit (at least {:.1f} GB for these {} plants); "
                    "export fewer plants, "
                    "use --glb-instancing, or obj/ply",
                    static_cast<double>(bin) / 1e9, s.plant_count()));
}

void write_glb(const Stand& s, PrototypeLibrary& lib, AtomicFile& out) {
  ChunkFile f(out);
  write_glb(ExportScope::whole(s), lib, f);
}

}  // namespace canopy
