#include "tools/organ_triangles.hpp"

#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include <fmt/format.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace canopy::check {

void OrganGeometry::add(double x, double y, double z) {
  v.emplace_back(x, y, z);
  const double c[3] = {x, y, z};
  for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], c[k]), hi[k] = std::max(hi[k], c[k]);
}

void read_obj_organs(const std::string& path, std::vector<OrganGeometry>& organs) {
  std::ifstream obj(path);
  if (!obj) throw std::runtime_error(path + ": cannot open");
  std::string line;
  long current = -1;
  std::vector<long> owner;
  while (std::getline(obj, line)) {
    if (line.rfind("g organ_", 0) == 0) current = std::stol(line.substr(8));
    else if (line.rfind("v ", 0) == 0) {
      double x, y, z;
      std::sscanf(line.c_str() + 2, "%lf %lf %lf", &x, &y, &z);
      owner.push_back(current);
      organs.at(static_cast<std::size_t>(current)).add(x, y, z);
    } else if (line.rfind("f ", 0) == 0) {
      std::istringstream in(line.substr(2));
      std::string t;
      std::array<int, 3> f{};
      for (int k = 0; k < 3 && (in >> t); ++k) {
        const long global = std::stol(t.substr(0, t.find('/'))) - 1;
        // Local index: vertices of an organ are contiguous in the file.
        long first = global;
        while (first > 0 && owner[static_cast<std::size_t>(first - 1)] == current) --first;
        f[k] = static_cast<int>(global - first);
      }
      organs.at(static_cast<std::size_t>(current)).f.push_back(f);
    }
  }
}

namespace {

/// Component `k` of element `i` of an accessor, decoded as glTF says (normalized integers too).
double component(const tinygltf::Model& m, const tinygltf::Accessor& a, std::size_t i, int k) {
  const tinygltf::BufferView& view = m.bufferViews.at(static_cast<std::size_t>(a.bufferView));
  const int size = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType));
  const int stride = a.ByteStride(view);
  const std::size_t at = view.byteOffset + a.byteOffset + i * static_cast<std::size_t>(stride) +
                         static_cast<std::size_t>(k * size);
  const unsigned char* p = m.buffers.at(static_cast<std::size_t>(view.buffer)).data.data() + at;
  double x = 0, scale = 1;
  switch (a.componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      std::int8_t v;
      std::memcpy(&v, p, 1);
      x = v;
      scale = 127;
      break;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      std::uint8_t v;
      std::memcpy(&v, p, 1);
      x = v;
      scale = 255;
      break;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      std::int16_t v;
      std::memcpy(&v, p, 2);
      x = v;
      scale = 32767;
      break;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t v;
      std::memcpy(&v, p, 2);
      x = v;
      scale = 65535;
      break;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      std::uint32_t v;
      std::memcpy(&v, p, 4);
      x = v;
      break;
    }
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float v;
      std::memcpy(&v, p, 4);
      x = v;
      break;
    }
    default: throw std::runtime_error(fmt::format("glb: component type {} not read", a.componentType));
  }
  return a.normalized ? std::max(x / scale, -1.0) : x;
}

std::array<double, 3> vec3(const std::vector<double>& v, double fill) {
  return v.size() == 3 ? std::array<double, 3>{v[0], v[1], v[2]} : std::array<double, 3>{fill, fill, fill};
}

}  // namespace

void read_glb_organs(const std::string& path, std::vector<OrganGeometry>& organs) {
  tinygltf::Model m;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  if (!loader.LoadBinaryFromFile(&m, &err, &warn, path)) throw std::runtime_error(path + ": " + err);
  const tinygltf::Node& root = m.nodes.at(0);
  const std::array<double, 3> origin = vec3(root.translation, 0);
  for (int child : root.children) {
    const tinygltf::Node& node = m.nodes.at(static_cast<std::size_t>(child));
    if (node.mesh < 0) continue;
    if (!node.rotation.empty() || !node.matrix.empty() || !node.children.empty())
      throw std::runtime_error(
          path + ": a plant node with a rotation, matrix or children (instanced glb) is not read");
    const std::array<double, 3> t = vec3(node.translation, 0), s = vec3(node.scale, 1);
    const double first =
        node.extras.Has("first_organ") ? node.extras.Get("first_organ").GetNumberAsDouble() : 0;
    for (const tinygltf::Primitive& prim : m.meshes.at(static_cast<std::size_t>(node.mesh)).primitives) {
      const tinygltf::Accessor& pos =
          m.accessors.at(static_cast<std::size_t>(prim.attributes.at("POSITION")));
      const tinygltf::Accessor& ids = m.accessors.at(static_cast<std::size_t>(prim.attributes.at("_ORGAN")));
      std::vector<std::pair<std::size_t, int>> where(pos.count);  // vertex -> organ, index in it
      for (std::size_t i = 0; i < pos.count; ++i) {
        double id = first + component(m, ids, i, 0);
        if (ids.type == TINYGLTF_TYPE_VEC2) id += 65536 * component(m, ids, i, 1);
        OrganGeometry& g = organs.at(static_cast<std::size_t>(id));
        double y_up[3];
        for (int k = 0; k < 3; ++k)
          y_up[k] = origin[static_cast<std::size_t>(k)] + t[static_cast<std::size_t>(k)] +
                    s[static_cast<std::size_t>(k)] * component(m, pos, i, k);
        where[i] = {static_cast<std::size_t>(id), static_cast<int>(g.v.size())};
        g.add(y_up[0], -y_up[2], y_up[1]);  // glTF's Y up back to Z up
      }
      const tinygltf::Accessor& idx = m.accessors.at(static_cast<std::size_t>(prim.indices));
      for (std::size_t i = 0; i + 2 < idx.count; i += 3) {
        std::array<int, 3> f{};
        const auto a = static_cast<std::size_t>(component(m, idx, i, 0));
        for (int k = 0; k < 3; ++k)
          f[static_cast<std::size_t>(k)] =
              where.at(static_cast<std::size_t>(component(m, idx, i + static_cast<std::size_t>(k), 0)))
                  .second;
        organs.at(where.at(a).first).f.push_back(f);
      }
    }
  }
}

}  // namespace canopy::check
