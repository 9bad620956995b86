// stand.glb: glTF 2.0 binary, streamed plant by plant. The JSON chunk comes first, so a first
// pass computes every count and POSITION bound; the second pass makes the same numbers again
// (same float operations) and writes them.
#include "geometry/export.hpp"
#include "geometry/organ_mesh.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>

namespace canopy {
namespace {

constexpr std::uint32_t kGlbMagic = 0x46546C67, kJsonChunk = 0x4E4F534A, kBinChunk = 0x004E4942;
constexpr std::size_t kFloatIdLimit = std::size_t(1) << 24;  // FLOAT holds organ ids exactly below this

struct Primitive {
  OrganKind kind;
  bool uv;
  std::vector<std::uint32_t> organs;
  std::size_t vertices = 0, indices = 0;
  Vec3f lo{std::numeric_limits<float>::max(), std::numeric_limits<float>::max(), std::numeric_limits<float>::max()};
  Vec3f hi{-std::numeric_limits<float>::max(), -std::numeric_limits<float>::max(), -std::numeric_limits<float>::max()};
};

struct PlantLayout {
  std::vector<Primitive> prims;
  std::size_t pos_bytes = 0, uv_bytes = 0, id_bytes = 0, index_bytes = 0;
  std::size_t bytes() const { return 2 * pos_bytes + uv_bytes + id_bytes + index_bytes; }
};

Vec3f glb_position(const Vec3d& off, Vec3f v) {
  return to_y_up({static_cast<float>(off.x + v.x), static_cast<float>(off.y + v.y), static_cast<float>(off.z + v.z)});
}

PlantLayout plan_plant(const Stand& s, std::size_t p, PrototypeLibrary& lib, std::size_t id_size) {
  PlantLayout L;
  const PlantRecord& pr = s.plants[p];
  // Primitives in kind order, organs with UVs (leaflet blades) apart from those without.
  for (std::size_t id = pr.first_organ; id < pr.first_organ + pr.organ_count; ++id) {
    const OrganRecord& r = s.organs[id];
    const bool uv = r.prototype == PrototypeKind::leaflet;
    auto it = std::find_if(L.prims.begin(), L.prims.end(), [&](const Primitive& q) { return q.kind == r.kind && q.uv == uv; });
    if (it == L.prims.end()) {
      L.prims.push_back({r.kind, uv, {}});
      it = L.prims.end() - 1;
    }
    it->organs.push_back(static_cast<std::uint32_t>(id));
  }
  std::stable_sort(L.prims.begin(), L.prims.end(),
                   [](const Primitive& a, const Primitive& b) { return std::make_pair(a.kind, a.uv) < std::make_pair(b.kind, b.uv); });
  const Vec3d off = s.offset(p);
  OrganMesh mesh;
  for (Primitive& q : L.prims) {
    for (std::uint32_t id : q.organs) {
      organ_mesh(s, id, lib, mesh);
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
    L.index_bytes += 4 * q.indices;
  }
  return L;
}

/// The plant's binary block: positions, normals, UVs, organ ids, indices (each primitive in turn).
void fill_plant(const Stand& s, std::size_t p, const PlantLayout& L, PrototypeLibrary& lib, bool float_ids,
                std::vector<char>& out) {
  out.assign(L.bytes(), 0);
  char* pos = out.data();
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
      const PrototypeMesh& pm = *mesh.prototype;
      for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        const Vec3f w = glb_position(off, mesh.positions[i]);
        const Vec3f n = to_y_up(mesh.normals[i]);
        std::memcpy(pos, &w, 12), pos += 12;
        std::memcpy(nrm, &n, 12), nrm += 12;
        if (q.uv) std::memcpy(uvp, pm.uvs[i].data(), 8), uvp += 8;
        if (float_ids) {
          const float f = static_cast<float>(id);
          std::memcpy(ids, &f, 4), ids += 4;
        } else {
          const std::uint16_t h[2] = {static_cast<std::uint16_t>(id & 0xffff), static_cast<std::uint16_t>(id >> 16)};
          std::memcpy(ids, h, 4), ids += 4;
        }
      }
      for (std::uint32_t k : pm.indices) {
        const std::uint32_t v = base + k;
        std::memcpy(idx, &v, 4), idx += 4;
      }
      base += static_cast<std::uint32_t>(mesh.positions.size());
    }
  }
}

}  // namespace

void write_glb(const Stand& s, PrototypeLibrary& lib, AtomicFile& out) {
  const bool float_ids = s.organ_count() <= kFloatIdLimit;
  const std::size_t n = s.plant_count();
  std::vector<PlantLayout> plan(n);
  for (const OrganRecord& r : s.organs) lib.get(r.prototype, r.lod);  // make meshes before threads share them
#pragma omp parallel for schedule(dynamic, 8)
  for (std::size_t p = 0; p < n; ++p) plan[p] = plan_plant(s, p, lib, 4);

  using json = nlohmann::json;
  json j;
  j["asset"] = {{"version", "2.0"}, {"generator", "canopy"}};
  j["scene"] = 0;
  json root = {{"name", "stand"},
               {"translation", {s.stand_origin.x, s.stand_origin.z, -s.stand_origin.y}},
               {"children", json::array()}};
  json nodes = json::array({root});
  json meshes = json::array(), accessors = json::array(), views = json::array(), materials = json::array();
  std::array<int, 7> material_of{};
  material_of.fill(-1);
  for (const auto& L : plan)
    for (const auto& q : L.prims) material_of[static_cast<std::size_t>(q.kind)] = 0;
  for (std::size_t k = 0; k < material_of.size(); ++k) {
    if (material_of[k] < 0) continue;
    material_of[k] = static_cast<int>(materials.size());
    const Vec3f c = kind_colour(static_cast<OrganKind>(k));
    materials.push_back({{"name", std::string(kOrganKindNames[k])},
                         {"doubleSided", true},
                         {"pbrMetallicRoughness", {{"baseColorFactor", {c.x, c.y, c.z, 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.8}}}});
  }
  std::size_t offset = 0;
  for (std::size_t p = 0; p < n; ++p) {
    const PlantLayout& L = plan[p];
    nodes[0]["children"].push_back(p + 1);
    if (L.prims.empty()) {  // a plant without organs: a node without a mesh
      nodes.push_back({{"name", "plant_" + std::to_string(p)}});
      continue;
    }
    const auto view = [&](std::size_t bytes, int stride, int target) {
      json v = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}, {"target", target}};
      if (stride) v["byteStride"] = stride;
      views.push_back(v);
      offset += bytes;
      return static_cast<int>(views.size() - 1);
    };
    const int vpos = view(L.pos_bytes, 12, 34962), vnrm = view(L.pos_bytes, 12, 34962);
    const int vuv = L.uv_bytes ? view(L.uv_bytes, 8, 34962) : -1;
    const int vid = view(L.id_bytes, 4, 34962), vidx = view(L.index_bytes, 0, 34963);
    std::size_t o_pos = 0, o_uv = 0, o_id = 0, o_idx = 0;
    json prims = json::array();
    for (const Primitive& q : L.prims) {
      const auto accessor = [&](int v, std::size_t off, int type_comp, std::size_t count, const char* type) {
        accessors.push_back({{"bufferView", v}, {"byteOffset", off}, {"componentType", type_comp}, {"count", count}, {"type", type}});
        return static_cast<int>(accessors.size() - 1);
      };
      const int apos = accessor(vpos, o_pos, 5126, q.vertices, "VEC3");
      accessors.back()["min"] = {q.lo.x, q.lo.y, q.lo.z};
      accessors.back()["max"] = {q.hi.x, q.hi.y, q.hi.z};
      json attrs = {{"POSITION", apos}, {"NORMAL", accessor(vnrm, o_pos, 5126, q.vertices, "VEC3")}};
      if (q.uv) attrs["TEXCOORD_0"] = accessor(vuv, o_uv, 5126, q.vertices, "VEC2");
      attrs["_ORGAN"] = float_ids ? accessor(vid, o_id, 5126, q.vertices, "SCALAR") : accessor(vid, o_id, 5123, q.vertices, "VEC2");
      const int aidx = accessor(vidx, o_idx, 5125, q.indices, "SCALAR");
      prims.push_back({{"attributes", attrs}, {"indices", aidx}, {"material", material_of[static_cast<std::size_t>(q.kind)]}, {"mode", 4}});
      o_pos += 12 * q.vertices;
      if (q.uv) o_uv += 8 * q.vertices;
      o_id += 4 * q.vertices;
      o_idx += 4 * q.indices;
    }
    nodes.push_back({{"name", "plant_" + std::to_string(p)}, {"mesh", meshes.size()}});
    meshes.push_back({{"name", "plant_" + std::to_string(p)}, {"primitives", prims}});
  }
  j["scenes"] = json::array({{{"nodes", {0}}}});
  j["nodes"] = nodes;
  if (!meshes.empty()) {
    j["meshes"] = meshes;
    j["accessors"] = accessors;
    j["bufferViews"] = views;
    j["materials"] = materials;
    j["buffers"] = json::array({{{"byteLength", offset}}});
  }
  if (!float_ids) j["extras"] = {{"_ORGAN", "VEC2 of UNSIGNED_SHORT: id = x + 65536 * y (more than 2^24 organs)"}};
  std::string text = j.dump();
  while (text.size() % 4) text.push_back(' ');
  const std::size_t bin = offset;  // every block is a multiple of 4 bytes
  const std::size_t total = 12 + 8 + text.size() + (bin ? 8 + bin : 0);
  if (total > 0xffffffffULL) throw std::runtime_error("stand.glb would exceed 4 GiB, the GLB limit; export fewer plants or use obj/ply");
  const std::uint32_t header[5] = {kGlbMagic, 2, static_cast<std::uint32_t>(total), static_cast<std::uint32_t>(text.size()), kJsonChunk};
  out.write(header, sizeof header);
  out.write(text);
  if (bin) {
    const std::uint32_t chunk[2] = {static_cast<std::uint32_t>(bin), kBinChunk};
    out.write(chunk, sizeof chunk);
    constexpr std::size_t kBatch = 64;
    std::vector<std::vector<char>> blocks(kBatch);
    for (std::size_t first = 0; first < n; first += kBatch) {
      const std::size_t last = std::min(n, first + kBatch);
#pragma omp parallel for schedule(dynamic, 1)
      for (std::size_t p = first; p < last; ++p) fill_plant(s, p, plan[p], lib, float_ids, blocks[p - first]);
      for (std::size_t p = first; p < last; ++p) out.write(blocks[p - first].data(), blocks[p - first].size());
    }
  }
}

}  // namespace canopy
