// The compact glb (KHR_mesh_quantization) read back with tinygltf: every vertex within half a
// step of the organ's own, normals and UVs within their rounding, organ ids exact, the same
// triangles; plants too large for their step keep float positions; a plant with more vertices
// in a primitive than 16-bit indices hold gets 32-bit ones; more organs than 16 bits number is
// refused. (Validator, three.js and the exact-predicate check on the quantized triangles run in
// the cli_stand and cgal_check suites.)
#include "geometry/export.hpp"
#include "tests/geometry/test_files.hpp"
#include "geometry/organ_mesh.hpp"
#include "lsystem/grow.hpp"

// test_export.cpp holds tinygltf's implementation, made with these settings.
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

using namespace canopy;
namespace fs = std::filesystem;

namespace {

std::string temp_dir() { return canopy::testing::temp_dir("compact"); }

GrowRequest request(const std::string& grammar, int steps, double x0 = 0) {
  GrowRequest req;
  req.grammar = grammar;
  RowLayout l;
  l.rows = 2;
  l.per_row = 2;
  l.jitter = 0.02;
  l.random_rotation = true;
  req.plants = row_layout(l);
  for (auto& p : req.plants) p.x += x0;
  req.steps = steps;
  req.lod = 1;
  return req;
}

/// Component k of element i of an accessor, as glTF decodes it.
double component(const tinygltf::Model& m, int accessor, std::size_t i, int k) {
  const auto& a = m.accessors[static_cast<std::size_t>(accessor)];
  const auto& v = m.bufferViews[static_cast<std::size_t>(a.bufferView)];
  const int size = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType));
  const unsigned char* p = m.buffers[0].data.data() + v.byteOffset + a.byteOffset +
                           i * static_cast<std::size_t>(a.ByteStride(v)) + static_cast<std::size_t>(k * size);
  switch (a.componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      std::int8_t x;
      std::memcpy(&x, p, 1);
      return a.normalized ? std::max(x / 127.0, -1.0) : x;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t x;
      std::memcpy(&x, p, 2);
      return a.normalized ? x / 65535.0 : x;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      std::uint32_t x;
      std::memcpy(&x, p, 4);
      return x;
    }
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float x;
      std::memcpy(&x, p, 4);
      return x;
    }
    default: FAIL("unexpected component type ", a.componentType); return 0;
  }
}

struct ReadBack {
  std::size_t quantized_plants = 0, float_plants = 0, wide_indices = 0, vertices = 0;
};

/// Writes `s` as a compact glb and checks it against the stand, vertex by vertex.
ReadBack check_compact(const Stand& s, const GlbCompactConfig& config) {
  const std::string dir = temp_dir();
  PrototypeLibrary lib;
  {
    OutputSet files(dir);
    write_glb_compact(s, lib, files.open("stand.glb"), config);
    files.commit_all();
  }
  tinygltf::Model m;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  REQUIRE(loader.LoadBinaryFromFile(&m, &err, &warn, dir + "/stand.glb"));
  CHECK(m.extensionsRequired == std::vector<std::string>{"KHR_mesh_quantization"});
  CHECK(m.nodes[0].translation == std::vector<double>{s.stand_origin.x, s.stand_origin.z, -s.stand_origin.y});
  ReadBack r;
  OrganMesh mesh;
  for (std::size_t p = 0; p < s.plant_count(); ++p) {
    const auto& node = m.nodes[p + 1];
    CHECK(node.name == "plant_" + std::to_string(p));
    const double step = node.scale.empty() ? 0 : node.scale[0];
    (step > 0 ? r.quantized_plants : r.float_plants)++;
    CHECK(step <= config.max_step);
    const auto first = static_cast<std::uint32_t>(node.extras.Get("first_organ").GetNumberAsInt());
    CHECK(first == s.plants[p].first_organ);
    const Vec3d off = s.offset(p);
    std::size_t organs_seen = 0;
    for (const auto& prim : m.meshes[static_cast<std::size_t>(node.mesh)].primitives) {
      const int pos = prim.attributes.at("POSITION"), nrm = prim.attributes.at("NORMAL"),
                ids = prim.attributes.at("_ORGAN");
      const std::size_t count = m.accessors[static_cast<std::size_t>(pos)].count;
      const int idx = prim.indices;
      r.wide_indices +=
          m.accessors[static_cast<std::size_t>(idx)].componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
      const bool uv = prim.attributes.count("TEXCOORD_0") > 0;
      std::size_t i = 0, t = 0;
      while (i < count) {
        // The organ of vertex i: its vertices come next, in the prototype's order.
        const std::uint32_t id = first + static_cast<std::uint32_t>(component(m, ids, i, 0));
        REQUIRE(id < s.plants[p].first_organ + s.plants[p].organ_count);
        CHECK(uv == (s.organs[id].prototype == PrototypeKind::leaflet));
        organ_mesh(s, id, lib, mesh);
        const std::size_t base = i;
        for (std::size_t k = 0; k < mesh.positions.size(); ++k, ++i) {
          REQUIRE(i < count);
          CHECK(first + component(m, ids, i, 0) == id);
          const Vec3f v = mesh.positions[k];
          const double want[3] = {off.x + v.x, off.z + v.z, -(off.y + v.y)};
          const double tol = step > 0 ? step / 2 * (1 + 1e-9) : 1e-6;
          for (int c = 0; c < 3; ++c) {
            const double got = node.translation[static_cast<std::size_t>(c)] +
                               (step > 0 ? step : 1) * component(m, pos, i, c);
            CHECK(std::fabs(got - want[c]) <= tol);
          }
          const Vec3f n = to_y_up(mesh.normals[k]);
          const float nw[3] = {n.x, n.y, n.z};
          for (int c = 0; c < 3; ++c) CHECK(std::fabs(component(m, nrm, i, c) - nw[c]) <= 0.5 / 127 + 1e-6);
          if (uv)
            for (int c = 0; c < 2; ++c)
              CHECK(std::fabs(component(m, prim.attributes.at("TEXCOORD_0"), i, c) -
                              mesh.prototype->uvs[k][static_cast<std::size_t>(c)]) <= 0.5 / 65535 + 1e-7);
        }
        for (std::uint32_t k : mesh.prototype->indices)
          CHECK(component(m, idx, t++, 0) == static_cast<double>(base + k));
        ++organs_seen;
      }
      r.vertices += count;
      CHECK(t == m.accessors[static_cast<std::size_t>(idx)].count);
    }
    CHECK(organs_seen == s.plants[p].organ_count);
  }
  fs::remove_all(dir);
  return r;
}

std::string write_grammar(const std::string& dir, const std::string& text) {
  const std::string path = dir + "/g.yaml";
  std::ofstream(path) << text;
  return path;
}

}  // namespace

TEST_CASE("compact glb reads back: positions within half a step, normals, UVs, ids, triangles") {
  const std::string tomato = std::string(CANOPY_SOURCE_DIR) + "/grammars/tomato.yaml";
  for (double x0 : {0.0, 1e6}) {  // a stand a thousand kilometres out keeps its steps
    INFO("x0 = " << x0);
    const Stand s = grow_stand(request(tomato, 12, x0));
    const ReadBack r = check_compact(s, {});
    CHECK(r.quantized_plants == s.plant_count());
    CHECK(r.float_plants == 0);
  }
  // Plants too large for 65,535 steps of at most 1 um keep FLOAT positions relative to the node.
  const Stand s = grow_stand(request(tomato, 12));
  const ReadBack r = check_compact(s, {1e-6});
  CHECK(r.float_plants == s.plant_count());
}

TEST_CASE("compact glb: 32-bit indices past 65,535 vertices a primitive; more organs than 16 bits refused") {
  const std::string dir = temp_dir();
  const std::string g = write_grammar(dir,
                                      "axiom: I(0.01,0.001)\n"
                                      "productions:\n  - I(a,b) -> I(a,b) I(a,b)\n"
                                      "organs:\n  I: {prototype: cylinder, kind: internode}\n");
  // 2^12 cylinders of 16 vertices at the coarsest level of detail: 65,536 vertices in one primitive.
  GrowRequest req = request(g, 12);
  req.plants.resize(1);
  const Stand wide = grow_stand(req);
  const ReadBack r = check_compact(wide, {});
  CHECK(r.vertices == 65536);
  CHECK(r.wide_indices == 1);
  req.steps = 17;  // 131,072 organs in one plant
  const Stand many = grow_stand(req);
  CHECK_THROWS_WITH_AS(check_glb_compact(ExportScope::whole(many)),
                       doctest::Contains("plant 0 has 131072 organs"), std::invalid_argument);
  PrototypeLibrary lib;
  fs::create_directories(dir + "/out");
  {
    OutputSet files(dir + "/out");
    CHECK_THROWS_AS(write_glb_compact(many, lib, files.open("stand.glb")), std::invalid_argument);
  }
  CHECK(!fs::exists(dir + "/out/stand.glb"));
  fs::remove_all(dir);
}
