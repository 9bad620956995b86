#pragma once
// docs/design.md's hard cases, each with its answer worked out by hand: triangle pairs (coplanar,
// touching, degenerate, slivers) and small hand-built stands (containment in solids, organs of
// zero thickness or length, leaflets at extreme scales). Shared by the CPU suite
// (test_hard_cases.cpp) and the CUDA suite, which checks the device gives the same answers.
#include "geometry/stand.hpp"
#include "geometry/vec.hpp"

#include <array>
#include <string>
#include <vector>

namespace canopy::test {

struct TrianglePairCase {
  std::string what;
  std::array<Vec3f, 3> a, b;
  bool meet;
};

inline std::vector<TrianglePairCase> hard_triangle_pairs() {
  return {
      {"coplanar, overlapping",
       {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}},
       {{{0.2f, 0.2f, 0}, {1.2f, 0.2f, 0}, {0.2f, 1.2f, 0}}},
       true},
      {"coplanar, one inside",
       {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}},
       {{{0.1f, 0.1f, 0}, {0.2f, 0.1f, 0}, {0.1f, 0.2f, 0}}},
       true},
      {"coplanar, apart",
       {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}},
       {{{0.6f, 0.6f, 0}, {1.6f, 0.6f, 0}, {0.6f, 1.6f, 0}}},
       false},
      {"shared edge, folded up",
       {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}},
       {{{0, 0, 0}, {1, 0, 0}, {0, 0, 1}}},
       true},
      {"crossing edges touching at a point",
       {{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}}},
       {{{1, -1, 0}, {1, -1, 1}, {1, 1, 0}}},
       true},
      {"a vertex on the face",
       {{{0, 0, 0}, {4, 0, 0}, {0, 4, 0}}},
       {{{1, 1, 0}, {2, 2, 3}, {1, 2, 3}}},
       true},
      {"the vertex a hair above the face",
       {{{0, 0, 0}, {4, 0, 0}, {0, 4, 0}}},
       {{{1, 1, 1e-6f}, {2, 2, 3}, {1, 2, 3}}},
       false},
      {"vertex on vertex", {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}, {{{0, 0, 0}, {-1, 0, 0}, {0, 0, -1}}}, true},
      {"a segment through a face",
       {{{0, 0, -1}, {0.2f, 0.2f, 1}, {0.1f, 0.1f, 0}}},
       {{{-1, -1, 0}, {2, -1, 0}, {-1, 2, 0}}},
       true},
      {"a segment beside a face",
       {{{5, 5, -1}, {5, 5, 1}, {5, 5, 0}}},
       {{{-1, -1, 0}, {2, -1, 0}, {-1, 2, 0}}},
       false},
      {"collinear segments overlapping",
       {{{0, 0, 0}, {1, 0, 0}, {0.5f, 0, 0}}},
       {{{0.5f, 0, 0}, {2, 0, 0}, {1.5f, 0, 0}}},
       true},
      {"collinear segments apart",
       {{{0, 0, 0}, {1, 0, 0}, {0.5f, 0, 0}}},
       {{{1.5f, 0, 0}, {2, 0, 0}, {1.7f, 0, 0}}},
       false},
      {"a point on a face",
       {{{0.3f, 0.3f, 0}, {0.3f, 0.3f, 0}, {0.3f, 0.3f, 0}}},
       {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}},
       true},
      {"a sliver crossing a triangle",
       {{{-1, 0.5f, 0}, {2, 0.5f, 0}, {2, 0.5001f, 0.0001f}}},
       {{{0, 0, -1}, {1, 0, 1}, {0, 1, 1}}},
       true},
  };
}

/// A stand of hand-placed organs: one plant, organs given by prototype, transform, kind.
struct Built {
  Stand stand;
  std::int32_t add(PrototypeKind proto, OrganKind kind, Affine3f m, float p0, float p1 = 0) {
    const auto id = static_cast<std::int32_t>(stand.organs.size());
    OrganRecord r;
    r.plant = 0;
    r.parent = -2 - id;  // every organ its own parent chain: nothing is adjacent
    r.kind = kind;
    r.prototype = proto;
    r.lod = 2;
    stand.organs.push_back(r);
    stand.transforms.push_back(m);
    stand.params.push_back({p0, p1});
    stand.joint_limit_deg.push_back(60);
    stand.plants[0].organ_count++;
    return id;
  }
  Built() {
    stand.plants.resize(1);
    stand.grammars = {"hand"};
  }
};

inline Affine3f frame(Vec3f h, Vec3f l, Vec3f t, float sx, float sy) {
  const Vec3f u = cross(h, l);
  return {h * sx, l * sy, u * sy, t};
}

/// A hand-built stand and the organ pairs whose answer is known.
struct BuiltCase {
  std::string what;
  Built built;
  std::vector<std::array<std::int32_t, 2>> touching, apart;
};

inline std::vector<BuiltCase> hard_built_stands() {
  std::vector<BuiltCase> out;
  {
    BuiltCase c{"a leaflet tip wholly inside a fruit or a stem, without crossing its surface", {}, {}, {}};
    Built& b = c.built;
    const auto fruit = b.add(PrototypeKind::sphere, OrganKind::fruit,
                             frame({0, 0, 1}, {0, -1, 0}, {0, 0, 0}, 0.02f, 0.02f), 0.02f);
    // Sphere centred at (0, 0, 0.02), radius 0.02: a 5 mm leaflet near the centre.
    const auto leaf = b.add(PrototypeKind::leaflet, OrganKind::leaflet,
                            frame({1, 0, 0}, {0, 1, 0}, {-0.002f, 0, 0.02f}, 0.005f, 0.003f), 0.005f, 0.003f);
    const auto stem = b.add(PrototypeKind::cylinder, OrganKind::internode,
                            frame({0, 0, 1}, {0, -1, 0}, {1, 0, 0}, 0.1f, 0.01f), 0.1f, 0.01f);
    const auto inside_stem =
        b.add(PrototypeKind::leaflet, OrganKind::leaflet,
              frame({0, 0, 1}, {0, 1, 0}, {1.002f, 0, 0.05f}, 0.01f, 0.004f), 0.01f, 0.004f);
    const auto outside =
        b.add(PrototypeKind::leaflet, OrganKind::leaflet,
              frame({1, 0, 0}, {0, 1, 0}, {0.03f, 0, 0.02f}, 0.005f, 0.003f), 0.005f, 0.003f);
    c.touching = {{fruit, leaf}, {stem, inside_stem}};
    c.apart = {{fruit, outside}, {fruit, stem}};
    out.push_back(c);
  }
  {
    BuiltCase c{"zero-thickness and zero-length organs", {}, {}, {}};
    Built& b = c.built;
    const auto blade = b.add(PrototypeKind::leaflet, OrganKind::leaflet,
                             frame({1, 0, 0}, {0, 1, 0}, {0, 0, 0}, 0.1f, 0.05f), 0.1f, 0.05f);
    // A cylinder of zero length standing on the blade, and one of zero radius through it.
    const auto flat = b.add(PrototypeKind::cylinder, OrganKind::petiole,
                            frame({0, 0, 1}, {0, -1, 0}, {0.03f, 0, 0}, 0.0f, 0.004f), 0.0f, 0.004f);
    const auto needle = b.add(PrototypeKind::cylinder, OrganKind::petiole,
                              frame({0, 0, 1}, {0, -1, 0}, {0.03f, 0, -0.01f}, 0.02f, 0.0f), 0.02f, 0.0f);
    const auto away = b.add(PrototypeKind::cylinder, OrganKind::petiole,
                            frame({0, 0, 1}, {0, -1, 0}, {0.3f, 0, -0.01f}, 0.02f, 0.0f), 0.02f, 0.0f);
    c.touching = {{blade, flat}, {blade, needle}};
    c.apart = {{blade, away}};
    out.push_back(c);
  }
  for (float scale : {0.01f, 1.0f, 100.0f}) {
    BuiltCase c{"leaflets at scale " + std::to_string(scale), {}, {}, {}};
    Built& b = c.built;
    const float l = 0.1f * scale, w = 0.05f * scale;
    const auto a =
        b.add(PrototypeKind::leaflet, OrganKind::leaflet, frame({1, 0, 0}, {0, 1, 0}, {0, 0, 0}, l, w), l, w);
    // Crossing blade (vertical, through the first's middle) and a parallel one just above.
    const auto x = b.add(PrototypeKind::leaflet, OrganKind::leaflet,
                         frame({0, 1, 0}, {0, 0, 1}, {0.3f * l, -0.2f * l, -0.01f * l}, l, w), l, w);
    const auto d = b.add(PrototypeKind::leaflet, OrganKind::leaflet,
                         frame({1, 0, 0}, {0, 1, 0}, {0, 0, 0.001f * l}, l, w), l, w);
    c.touching = {{a, x}};
    c.apart = {{a, d}};
    out.push_back(c);
  }
  return out;
}

}  // namespace canopy::test
