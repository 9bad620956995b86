// Exports read back: glTF (tinygltf), OBJ and PLY parsed here, organs.csv round trip, byte-identical
// reruns at any thread count.
#include "geometry/export.hpp"
#include "tests/geometry/test_files.hpp"
#include "geometry/organ_mesh.hpp"
#include "lsystem/grow.hpp"

#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include <doctest/doctest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

using namespace canopy;
namespace fs = std::filesystem;

using canopy::testing::slurp;

namespace {

std::string temp_dir() { return canopy::testing::temp_dir("export"); }

Stand small_stand(int threads = 0, double x0 = 0) {
  GrowRequest req;
  req.grammar = std::string(CANOPY_SOURCE_DIR) + "/grammars/tomato.yaml";
  RowLayout l;
  l.rows = 2;
  l.per_row = 3;
  l.jitter = 0.02;
  l.random_rotation = true;
  req.plants = row_layout(l);
  for (auto& p : req.plants) p.x += x0;
  req.steps = 12;
  req.lod = 1;
  req.threads = threads;
  return grow_stand(req);
}

void export_all(const Stand& s, const std::string& dir) {
  PrototypeLibrary lib;
  OutputSet files(dir);
  write_glb(s, lib, files.open("stand.glb"));
  write_obj(s, lib, files.open("stand.obj"), files.open("stand.mtl"), "stand.mtl");
  write_ply(s, lib, files.open("stand.ply"));
  write_organs_csv(s, lib, files.open("organs.csv"));
  write_plants_csv(s, files.open("plants.csv"));
  files.commit_all();
}

}  // namespace

TEST_CASE("glb reads back: nodes per plant, organ ids, counts, Y-up positions") {
  const Stand s = small_stand();
  const std::string dir = temp_dir();
  export_all(s, dir);
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  REQUIRE(loader.LoadBinaryFromFile(&model, &err, &warn, dir + "/stand.glb"));
  REQUIRE(model.nodes.size() == s.plant_count() + 1);
  const auto& root = model.nodes[0];
  REQUIRE(root.translation.size() == 3);
  CHECK(root.translation[0] == s.stand_origin.x);
  CHECK(root.translation[2] == -s.stand_origin.y);
  PrototypeLibrary lib;
  std::set<std::string> materials;
  for (const auto& m : model.materials) materials.insert(m.name);
  CHECK(materials.count("leaflet"));
  CHECK(materials.count("internode"));
  for (std::size_t p = 0; p < s.plant_count(); ++p) {
    const auto& node = model.nodes[p + 1];
    CHECK(node.name == "plant_" + std::to_string(p));
    const auto& mesh = model.meshes[static_cast<std::size_t>(node.mesh)];
    std::map<int, std::size_t> vertices_of;  // organ -> vertices seen
    std::size_t triangles = 0;
    for (const auto& prim : mesh.primitives) {
      const auto& ids = model.accessors[static_cast<std::size_t>(prim.attributes.at("_ORGAN"))];
      const auto& view = model.bufferViews[static_cast<std::size_t>(ids.bufferView)];
      const float* f =
          reinterpret_cast<const float*>(model.buffers[0].data.data() + view.byteOffset + ids.byteOffset);
      for (std::size_t i = 0; i < ids.count; ++i) ++vertices_of[static_cast<int>(f[i])];
      triangles += model.accessors[static_cast<std::size_t>(prim.indices)].count / 3;
      const std::string kind = model.materials[static_cast<std::size_t>(prim.material)].name;
      CHECK(prim.attributes.count("TEXCOORD_0") == (kind == "leaflet" ? 1u : 0u));
      // Every vertex of this primitive belongs to an organ of this kind.
      for (std::size_t i = 0; i < ids.count; ++i)
        CHECK(name_of(s.organs[static_cast<std::size_t>(f[i])].kind) == kind);
    }
    const PlantRecord& pr = s.plants[p];
    CHECK(vertices_of.size() == pr.organ_count);
    std::size_t want_tris = 0;
    for (std::uint32_t id = pr.first_organ; id < pr.first_organ + pr.organ_count; ++id) {
      const PrototypeMesh& pm = lib.get(s.organs[id]);
      CHECK(vertices_of[static_cast<int>(id)] == pm.positions.size());
      want_tris += pm.triangle_count();
    }
    CHECK(triangles == want_tris);
  }
  // The first vertex of the first plant's first primitive, by hand.
  const auto& prim = model.meshes[0].primitives[0];
  const auto& acc = model.accessors[static_cast<std::size_t>(prim.attributes.at("POSITION"))];
  const auto& view = model.bufferViews[static_cast<std::size_t>(acc.bufferView)];
  const float* v =
      reinterpret_cast<const float*>(model.buffers[0].data.data() + view.byteOffset + acc.byteOffset);
  const auto& ids = model.accessors[static_cast<std::size_t>(prim.attributes.at("_ORGAN"))];
  const auto& iview = model.bufferViews[static_cast<std::size_t>(ids.bufferView)];
  const std::size_t organ = static_cast<std::size_t>(
      *reinterpret_cast<const float*>(model.buffers[0].data.data() + iview.byteOffset + ids.byteOffset));
  const Vec3f local = apply(s.transforms[organ], lib.get(s.organs[organ]).positions[0]);
  CHECK(v[0] == doctest::Approx(local.x).epsilon(1e-6));
  CHECK(v[1] == doctest::Approx(local.z).epsilon(1e-6));
  CHECK(v[2] == doctest::Approx(-local.y).epsilon(1e-6));
  fs::remove_all(dir);
}

/// Every triangle of every primitive, read through its indices (UNSIGNED_SHORT or UNSIGNED_INT),
/// is its organ's prototype triangle: its corners carry one organ id and sit at the organ's first
/// vertex plus the prototype's indices. Returns the index component types seen.
static std::set<int> check_glb_triangles(const Stand& s, const std::string& file) {
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  REQUIRE(loader.LoadBinaryFromFile(&model, &err, &warn, file));
  PrototypeLibrary lib;
  std::set<int> types;
  const auto bytes = [&](const tinygltf::Accessor& a) {
    const auto& v = model.bufferViews[static_cast<std::size_t>(a.bufferView)];
    return model.buffers[0].data.data() + v.byteOffset + a.byteOffset;
  };
  for (std::size_t p = 0; p < s.plant_count(); ++p) {
    const auto& mesh = model.meshes[static_cast<std::size_t>(model.nodes[p + 1].mesh)];
    std::size_t most = 0;  // the plant's largest primitive, in vertices
    for (const auto& prim : mesh.primitives)
      most = std::max(most, model.accessors[static_cast<std::size_t>(prim.attributes.at("POSITION"))].count);
    for (const auto& prim : mesh.primitives) {
      const auto& ia = model.accessors[static_cast<std::size_t>(prim.indices)];
      types.insert(ia.componentType);
      // The plant's primitives share one index size: short where its largest fits below 65,535.
      CHECK(ia.componentType ==
            (most <= 65535 ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT : TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT));
      const auto index = [&](std::size_t k) -> std::uint32_t {
        if (ia.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
          std::uint16_t v;
          std::memcpy(&v, bytes(ia) + 2 * k, 2);
          return v;
        }
        std::uint32_t v;
        std::memcpy(&v, bytes(ia) + 4 * k, 4);
        return v;
      };
      const auto& ida = model.accessors[static_cast<std::size_t>(prim.attributes.at("_ORGAN"))];
      const float* ids = reinterpret_cast<const float*>(bytes(ida));
      std::map<std::uint32_t, std::uint32_t> first_vertex;  // organ -> its first vertex here
      for (std::uint32_t v = 0; v < ida.count; ++v)
        first_vertex.emplace(static_cast<std::uint32_t>(ids[v]), v);
      std::map<std::uint32_t, std::size_t> seen;  // organ -> indices read
      std::size_t wrong = 0;                      // indices that are not the prototype's
      for (std::size_t k = 0; k < ia.count; ++k) {
        const std::uint32_t v = index(k);
        REQUIRE(v < ida.count);
        const auto organ = static_cast<std::uint32_t>(ids[v]);
        const PrototypeMesh& pm = lib.get(s.organs[organ]);
        const std::size_t at = seen[organ]++;
        REQUIRE(at < pm.indices.size());
        wrong += v != first_vertex.at(organ) + pm.indices[at];
      }
      CHECK(wrong == 0);
      for (const auto& [organ, n] : seen) CHECK(n == lib.get(s.organs[organ]).indices.size());
    }
  }
  return types;
}

TEST_CASE("glb indices: each organ's own triangles, short where a plant's primitives fit") {
  const std::string dir = temp_dir();
  const auto write = [&](const Stand& s) {
    PrototypeLibrary lib;
    OutputSet files(dir);
    write_glb(s, lib, files.open("stand.glb"));
    files.commit_all();
  };
  const Stand small = small_stand();
  write(small);
  CHECK(check_glb_triangles(small, dir + "/stand.glb") ==
        std::set<int>{TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT});
  // One mature plant at the finest level of detail: its leaflets pass 65,535 vertices.
  GrowRequest req;
  req.grammar = std::string(CANOPY_SOURCE_DIR) + "/grammars/tomato_mature.yaml";
  req.plants = {PlantPlacement{}, PlantPlacement{}};
  req.plants[1].x = 1;
  req.lod = 16;
  const Stand big = grow_stand(req);
  write(big);
  CHECK(check_glb_triangles(big, dir + "/stand.glb").count(TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT));
  fs::remove_all(dir);
}

TEST_CASE("obj and ply read back: groups, faces and ids per organ") {
  const Stand s = small_stand();
  const std::string dir = temp_dir();
  export_all(s, dir);
  PrototypeLibrary lib;
  std::ifstream obj(dir + "/stand.obj");
  std::string line;
  int plants = 0;
  long organ = -1;
  std::map<long, std::size_t> faces;
  std::set<std::string> materials;
  while (std::getline(obj, line)) {
    if (line.rfind("o plant_", 0) == 0) ++plants;
    else if (line.rfind("g organ_", 0) == 0) organ = std::stol(line.substr(8));
    else if (line.rfind("f ", 0) == 0) ++faces[organ];
    else if (line.rfind("usemtl ", 0) == 0) {
      materials.insert(line.substr(7));
      CHECK(line.substr(7) == name_of(s.organs[static_cast<std::size_t>(organ)].kind));
    }
  }
  CHECK(plants == static_cast<int>(s.plant_count()));
  CHECK(faces.size() == s.organ_count());
  for (std::size_t id = 0; id < s.organ_count(); ++id)
    CHECK(faces[static_cast<long>(id)] == lib.get(s.organs[id]).triangle_count());
  CHECK(slurp(dir + "/stand.mtl").find("newmtl leaflet") != std::string::npos);

  const std::string ply = slurp(dir + "/stand.ply");
  const std::size_t end = ply.find("end_header\n");
  REQUIRE(end != std::string::npos);
  const std::string header = ply.substr(0, end);
  std::size_t nv = 0, nf = 0;
  std::sscanf(header.c_str() + header.find("element vertex"), "element vertex %zu", &nv);
  std::sscanf(header.c_str() + header.find("element face"), "element face %zu", &nf);
  CHECK(header.find("comment stand_origin ") != std::string::npos);
  const char* face = ply.data() + end + 11 + nv * 24;
  std::map<int, std::size_t> per_organ;
  for (std::size_t f = 0; f < nf; ++f, face += 21) {
    REQUIRE(face[0] == 3);
    std::int32_t ids[5];
    std::memcpy(ids, face + 1, sizeof ids);
    CHECK(ids[3] == s.organs[static_cast<std::size_t>(ids[4])].plant);
    for (int k = 0; k < 3; ++k) CHECK(static_cast<std::size_t>(ids[k]) < nv);
    ++per_organ[ids[4]];
  }
  CHECK(face == ply.data() + ply.size());
  CHECK(per_organ.size() == s.organ_count());
  fs::remove_all(dir);
}

TEST_CASE("organs.csv reads back bit for bit, and the files are byte-identical at any thread count") {
  const Stand a = small_stand(1), b = small_stand(2);
  const std::string d1 = temp_dir(), d2 = temp_dir(), d3 = temp_dir();
  export_all(a, d1);
  export_all(b, d2);
  const Stand back = read_stand(d1);
  REQUIRE(back.organ_count() == a.organ_count());
  CHECK(std::memcmp(back.transforms.data(), a.transforms.data(), a.transforms.size() * sizeof(Affine3f)) ==
        0);
  CHECK(std::memcmp(back.organs.data(), a.organs.data(), a.organs.size() * sizeof(OrganRecord)) == 0);
  for (std::size_t p = 0; p < a.plant_count(); ++p) {
    CHECK(back.plants[p].first_organ == a.plants[p].first_organ);
    CHECK(back.plants[p].first_leaf == a.plants[p].first_leaf);
    CHECK(back.plants[p].leaf_count == a.plants[p].leaf_count);
    CHECK(back.plants[p].x == a.plants[p].x);
  }
  export_all(back, d3);
  for (const char* f : {"stand.glb", "stand.obj", "stand.ply", "organs.csv", "plants.csv"}) {
    INFO(f);
    CHECK(slurp(d1 + "/" + f) == slurp(d2 + "/" + f));
    CHECK(slurp(d1 + "/" + f) == slurp(d3 + "/" + f));
  }
  for (const auto& d : {d1, d2, d3}) fs::remove_all(d);
}

TEST_CASE("a stand 10^6 m from the origin keeps micrometres in the OBJ") {
  const Stand s = small_stand(0, 1e6);
  const std::string dir = temp_dir();
  export_all(s, dir);
  std::ifstream obj(dir + "/stand.obj");
  std::string line;
  while (std::getline(obj, line) && line.rfind("v ", 0) != 0) {
  }
  double x = 0, y = 0, z = 0;
  std::sscanf(line.c_str(), "v %lf %lf %lf", &x, &y, &z);
  PrototypeLibrary lib;
  const Vec3f local = apply(s.transforms[0], lib.get(s.organs[0]).positions[0]);
  CHECK(std::fabs(x - (s.plants[0].x + static_cast<double>(local.x))) < 1e-6);
  CHECK(std::fabs(y - (s.plants[0].y + static_cast<double>(local.y))) < 1e-6);
  CHECK(s.stand_origin.x > 999999);
  fs::remove_all(dir);
}

TEST_CASE("a failed run leaves no file behind") {
  const std::string dir = temp_dir();
  {
    OutputSet files(dir);
    files.open("stand.obj").write("partial");
    // destroyed without commit_all, as when an exception unwinds a run
  }
  CHECK(fs::is_empty(dir));
  fs::remove_all(dir);
  CHECK_THROWS_AS(prepare_output_dir("/proc/canopy-cannot-write-here"), std::runtime_error);
}

TEST_CASE("instanced glb: every organ's translation, rotation and scale give back its vertices") {
  const Stand s = small_stand();
  const std::string dir = temp_dir();
  PrototypeLibrary lib;
  {
    OutputSet files(dir);
    write_glb_instanced(s, lib, files.open("stand.glb"));
    files.commit_all();
  }
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  REQUIRE(loader.LoadBinaryFromFile(&model, &err, &warn, dir + "/stand.glb"));
  const auto floats = [&](int accessor) {
    const auto& a = model.accessors[static_cast<std::size_t>(accessor)];
    const auto& v = model.bufferViews[static_cast<std::size_t>(a.bufferView)];
    return reinterpret_cast<const float*>(model.buffers[0].data.data() + v.byteOffset + a.byteOffset);
  };
  std::size_t seen = 0;
  for (std::size_t p = 0; p < s.plant_count(); ++p) {
    const auto& plant = model.nodes[p + 1];
    CHECK(plant.name == "plant_" + std::to_string(p));
    for (int child : plant.children) {
      const auto& node = model.nodes[static_cast<std::size_t>(child)];
      const auto& ext = node.extensions.at("EXT_mesh_gpu_instancing").Get("attributes");
      const float* t = floats(ext.Get("TRANSLATION").GetNumberAsInt());
      const float* q = floats(ext.Get("ROTATION").GetNumberAsInt());
      const float* sc = floats(ext.Get("SCALE").GetNumberAsInt());
      const float* id = floats(ext.Get("_ORGAN").GetNumberAsInt());
      const std::size_t n =
          model.accessors[static_cast<std::size_t>(ext.Get("_ORGAN").GetNumberAsInt())].count;
      const auto& prim = model.meshes[static_cast<std::size_t>(node.mesh)].primitives[0];
      const float* pos = floats(prim.attributes.at("POSITION"));
      const std::size_t nv = model.accessors[static_cast<std::size_t>(prim.attributes.at("POSITION"))].count;
      for (std::size_t i = 0; i < n; ++i, ++seen) {
        const std::size_t organ = static_cast<std::size_t>(id[i]);
        CHECK(static_cast<std::size_t>(s.organs[organ].plant) == p);
        const PrototypeMesh& pm = lib.get(s.organs[organ]);
        REQUIRE(nv == pm.positions.size());
        for (std::size_t k = 0; k < nv; k += 5) {
          // S, then R (unit quaternion), then T: the plant-frame vertex.
          const Vec3d v{pos[3 * k] * sc[3 * i], pos[3 * k + 1] * sc[3 * i + 1],
                        pos[3 * k + 2] * sc[3 * i + 2]};
          const Vec3d u{q[4 * i], q[4 * i + 1], q[4 * i + 2]};
          const double w = q[4 * i + 3];
          const Vec3d r = v + cross(u, cross(u, v) + v * w) * 2.0;
          const Vec3d got = r + Vec3d{t[3 * i], t[3 * i + 1], t[3 * i + 2]};
          const Vec3f want = apply(s.transforms[organ], pm.positions[k]);
          CHECK(length(got - to_double(want)) < 1e-6);
        }
      }
    }
  }
  CHECK(seen == s.organ_count());
  fs::remove_all(dir);
}
