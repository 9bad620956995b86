#pragma once
// Stands for the collision suites, and the brute-force oracle they are checked against.
#include "collision/backend.hpp"
#include "collision/exact.hpp"
#include "geometry/triangle_distance.hpp"
#include "lsystem/grow.hpp"

#include <doctest/doctest.h>

#include <cstdlib>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>

namespace canopy::test {

/// A file of the source tree; CANOPY_SOURCE_DIR in the environment overrides the build's path
/// (tests run on another machine, from a copy of the tree).
inline std::string source(const std::string& relative) {
  if (const char* e = std::getenv("CANOPY_SOURCE_DIR")) return std::string(e) + "/" + relative;
  return std::string(CANOPY_SOURCE_DIR) + "/" + relative;
}

/// A seeded random small stand: 2-20 plants of the tomato at a random age, rows or a cluster
/// of random positions (dense), random rotations, sometimes two plants on one spot.
inline Stand random_stand(std::uint64_t seed, int max_plants = 20) {
  std::mt19937_64 g(seed);
  GrowRequest req;
  req.grammar = source("grammars/tomato.yaml");
  const int n = 2 + static_cast<int>(g() % static_cast<std::uint64_t>(max_plants - 1));
  const bool dense = g() % 2;
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < n; ++i) {
    PlantPlacement p;
    p.x = dense ? u(g) * 0.6 : (i % 5) * 0.4 + 0.02 * u(g);
    p.y = dense ? u(g) * 0.6 : (i / 5) * 1.0 + 0.02 * u(g);
    p.rotation_deg = 360 * u(g);
    p.seed = g() % 1000;
    req.plants.push_back(p);
  }
  if (g() % 3 == 0) req.plants.back() = req.plants.front();  // two plants on one spot
  req.steps = 9 + static_cast<int>(g() % 8);
  req.lod = 1 + static_cast<int>(g() % 2);
  return grow_stand(req);
}

/// A seeded random stand in rows at the default spacing (1.0 m x 0.4 m) or dense (0.25 m x
/// 0.25 m), jittered and rotated, 4-12 plants at a random age: no two plants on one spot.
inline Stand row_stand(std::uint64_t seed) {
  std::mt19937_64 g(seed * 7919);
  std::uniform_real_distribution<double> u(0, 1);
  GrowRequest req;
  req.grammar = source("grammars/tomato.yaml");
  const bool dense = seed % 2 == 0;
  const int n = 4 + static_cast<int>(g() % 9), per_row = 2 + static_cast<int>(g() % 3);
  for (int i = 0; i < n; ++i) {
    PlantPlacement p;
    p.x = (i % per_row) * (dense ? 0.25 : 0.4) + 0.02 * u(g);
    p.y = (i / per_row) * (dense ? 0.25 : 1.0) + 0.02 * u(g);
    p.rotation_deg = 360 * u(g);
    p.seed = g() % 1000;
    req.plants.push_back(p);
  }
  req.steps = 12 + static_cast<int>(g() % 8);
  req.lod = 1 + static_cast<int>(g() % 2);
  return grow_stand(req);
}

/// A seeded random small stand of curved-leaflet tomatoes (grammars/tomato_mature.yaml at a
/// random age) whose leaflets take every bend, cup and fold the shape code holds, at level of
/// detail `lod`: dense rows or a cluster, random rotations.
inline Stand curved_stand(std::uint64_t seed, int lod) {
  std::mt19937_64 g(seed * 104729);
  std::uniform_real_distribution<double> u(0, 1);
  GrowRequest req;
  req.grammar = source("grammars/tomato_mature.yaml");
  for (const char* o :
       {"bend_min=-80", "bend_max=70", "cup_min=-30", "cup_max=15", "fold_min=0", "fold_max=30"})
    req.load.overrides.push_back(parse_override(o));
  const int n = 3 + static_cast<int>(g() % 4);
  const bool cluster = g() % 2;
  for (int i = 0; i < n; ++i) {
    PlantPlacement p;
    p.x = cluster ? u(g) * 0.5 : (i % 3) * 0.3 + 0.02 * u(g);
    p.y = cluster ? u(g) * 0.5 : (i / 3) * 0.5 + 0.02 * u(g);
    p.rotation_deg = 360 * u(g);
    p.seed = g() % 1000;
    req.plants.push_back(p);
  }
  req.steps = 10 + static_cast<int>(g() % 7);
  req.lod = lod;
  return grow_stand(req);
}

/// All organ pairs (a < b) of kinds in `collide`, not adjacent, whose triangles meet (every
/// triangle pair tested) or one inside the other's solid. The only filter is the organs' own
/// vertex boxes, which any two meeting organs share.
inline std::vector<Contact> brute_force_exact(const Stand& s, const KindMask& collide, float clearance = 0) {
  PrototypeLibrary lib;
  const std::size_t n = s.organ_count();
  std::vector<std::vector<Vec3f>> verts(n);
  std::vector<std::array<double, 6>> box(n);
  for (std::size_t i = 0; i < n; ++i) {
    const OrganRecord& r = s.organs[i];
    organ_vertices(s, lib.get(r), static_cast<std::int32_t>(i), 0, verts[i]);
    box[i] = {1e300, 1e300, 1e300, -1e300, -1e300, -1e300};
    for (const Vec3f& v : verts[i]) {
      box[i][0] = std::min<double>(box[i][0], v.x), box[i][1] = std::min<double>(box[i][1], v.y),
      box[i][2] = std::min<double>(box[i][2], v.z);
      box[i][3] = std::max<double>(box[i][3], v.x), box[i][4] = std::max<double>(box[i][4], v.y),
      box[i][5] = std::max<double>(box[i][5], v.z);
    }
  }
  std::vector<Contact> out;
  ExactScratch scratch;
  for (std::size_t a = 0; a < n; ++a) {
    if (!collide[static_cast<std::size_t>(s.organs[a].kind)]) continue;
    for (std::size_t b = a + 1; b < n; ++b) {
      if (!collide[static_cast<std::size_t>(s.organs[b].kind)]) continue;
      if (adjacent(s.organs[a], static_cast<std::int32_t>(a), s.organs[b], static_cast<std::int32_t>(b)))
        continue;
      bool far = false;
      for (int k = 0; k < 3; ++k)
        if (box[a][k] > box[b][k + 3] + clearance + 1e-3 || box[b][k] > box[a][k + 3] + clearance + 1e-3)
          far = true;
      if (far) continue;
      // Every triangle pair, in the frame of a's plant (as the detection computes them).
      const OrganRecord& ra = s.organs[a];
      const OrganRecord& rb = s.organs[b];
      const PrototypeMesh& ma = lib.get(ra);
      const PrototypeMesh& mb = lib.get(rb);
      std::vector<Vec3f> va, vb;
      organ_vertices(s, ma, static_cast<std::int32_t>(a), ra.plant, va);
      organ_vertices(s, mb, static_cast<std::int32_t>(b), ra.plant, vb);
      bool hit = false;
      for (std::size_t i = 0; i < ma.triangle_count() && !hit; ++i)
        for (std::size_t j = 0; j < mb.triangle_count() && !hit; ++j) {
          const Vec3f ta[3] = {va[ma.indices[3 * i]], va[ma.indices[3 * i + 1]], va[ma.indices[3 * i + 2]]};
          const Vec3f tb[3] = {vb[mb.indices[3 * j]], vb[mb.indices[3 * j + 1]], vb[mb.indices[3 * j + 2]]};
          hit = clearance > 0 ? triangles_within(ta, tb, clearance) : triangles_intersect(ta, tb);
        }
      if (!hit && is_solid(rb.prototype))
        hit = point_in_convex(d3(va[0]), vb.data(), mb.indices.data(), static_cast<int>(mb.triangle_count()));
      if (!hit && is_solid(ra.prototype))
        hit = point_in_convex(d3(vb[0]), va.data(), ma.indices.data(), static_cast<int>(ma.triangle_count()));
      if (hit)
        out.push_back(
            {static_cast<std::int32_t>(a), static_cast<std::int32_t>(b), ra.plant, rb.plant, -1, -1});
    }
  }
  return out;
}

/// `n` plants on one spot, turned apart.
inline Stand on_one_spot(int n, int steps = 10) {
  GrowRequest req;
  req.grammar = source("grammars/tomato.yaml");
  for (int i = 0; i < n; ++i) {
    PlantPlacement p;
    p.rotation_deg = 37.0 * i;
    p.seed = static_cast<std::uint64_t>(i + 1);
    req.plants.push_back(p);
  }
  req.steps = steps;
  req.lod = 1;
  return grow_stand(req);
}

inline std::string failure(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

}  // namespace canopy::test
