#include "geometry/organ_mesh.hpp"

#include "geometry/atomic_file.hpp"
#include "geometry/first_exception.hpp"

#include <omp.h>

#include <array>
#include <chrono>
#include <future>

namespace canopy {

Affine3f cofactor(const Affine3f& m) {
  return {cross(m.c1, m.c2), cross(m.c2, m.c0), cross(m.c0, m.c1), {0, 0, 0}};
}

Vec3f transform_normal(const Affine3f& m, Vec3f n) { return transform_normal(m, cofactor(m), n); }

Vec3f transform_normal(const Affine3f& m, const Affine3f& cof, Vec3f n) {
  const Vec3f r = apply_linear(cof, n);
  const float len = length(r);
  if (len > 0 && std::isfinite(len)) return r * (1 / len);
  const Vec3f d = apply_linear(m, n);  // degenerate (zero-length or zero-width) organ
  const float dl = length(d);
  if (dl > 0) return d * (1 / dl);
  return {0, 0, 1};
}

void organ_mesh(const Stand& stand, std::size_t id, PrototypeLibrary& library, OrganMesh& out,
                bool positions_only) {
  const OrganRecord& r = stand.organs[id];
  const Affine3f& m = stand.transforms[id];
  out.prototype = &library.get(r);
  const auto& pm = *out.prototype;
  out.positions.resize(pm.positions.size());
  for (std::size_t i = 0; i < pm.positions.size(); ++i) out.positions[i] = apply(m, pm.positions[i]);
  if (positions_only) return;
  const Affine3f cof = cofactor(m);
  out.normals.resize(pm.normals.size());
  for (std::size_t i = 0; i < pm.normals.size(); ++i)
    out.normals[i] = transform_normal(m, cof, pm.normals[i]);
}

namespace {

// The exporting thread waits for the writer thread (the time is the file's, as waited).
void wait(std::future<void>& writing, AtomicFile& out) {
  if (!writing.valid()) return;
  const auto t = std::chrono::steady_clock::now();
  writing.get();
  out.add_waited(std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count());
}

}  // namespace

void write_ordered(AtomicFile& out, std::size_t n, std::size_t chunk,
                   const std::function<void(std::size_t, std::size_t, std::string&)>& write) {
  // Two sets of buffers: while one wave is written (by another thread), the next is formatted.
  const std::size_t chunks = (n + chunk - 1) / chunk;
  const std::size_t wave = static_cast<std::size_t>(std::max(1, omp_get_max_threads())) * 4;
  std::vector<std::string> bufs[2] = {std::vector<std::string>(wave), std::vector<std::string>(wave)};
  std::future<void> writing;
  int cur = 0;
  for (std::size_t first = 0; first < chunks; first += wave, cur ^= 1) {
    const std::size_t last = std::min(chunks, first + wave);
    std::vector<std::string>& b = bufs[cur];
    // The first exception is thrown once the wave is done (geometry/first_exception.hpp).
    FirstException failed;
#pragma omp parallel for schedule(dynamic, 1)
    for (std::size_t c = first; c < last; ++c) {
      try {
        b[c - first].clear();
        write(c * chunk, std::min(n, (c + 1) * chunk), b[c - first]);
      } catch (...) {
        failed.keep();
      }
    }
    if (failed.caught()) {
      if (writing.valid()) writing.wait();
      failed.rethrow();
    }
    wait(writing, out);
    writing = std::async(std::launch::async, [&out, &b, count = last - first] {
      for (std::size_t k = 0; k < count; ++k) out.write_behind(b[k]);
    });
  }
  wait(writing, out);
}

std::vector<const PrototypeMesh*> make_meshes(const Stand& s, PrototypeLibrary& lib, int threads) {
  const int t = threads > 0 ? threads : omp_get_max_threads();
  // Which (prototype, lod, shape) slots occur; an organ the library would refuse (a level of
  // detail out of range, a shape on another prototype than the leaflet) is left to it.
  std::vector<std::uint8_t> used(kMeshSlots, 0);
  bool odd = false;
#pragma omp parallel num_threads(t) reduction(|| : odd)
  {
    std::vector<std::uint8_t> mine(kMeshSlots, 0);
#pragma omp for schedule(static) nowait
    for (std::size_t k = 0; k < s.organ_count(); ++k) {
      const OrganRecord& r = s.organs[k];
      if (r.lod >= 1 && r.lod <= kMaxLod && (r.shape == 0 || r.prototype == PrototypeKind::leaflet))
        mine[static_cast<std::size_t>(mesh_slot(r.prototype, r.lod, r.shape))] = 1;
      else odd = true;
    }
#pragma omp critical
    for (std::size_t i = 0; i < used.size(); ++i) used[i] = used[i] | mine[i];
  }
  if (odd)  // the library reports it, at the first such organ
    for (const OrganRecord& r : s.organs) lib.get(r);
  std::vector<const PrototypeMesh*> meshes(kMeshSlots, nullptr);
  for (std::size_t p = 0; p < kPrototypeNames.size(); ++p)
    for (int l = 1; l <= kMaxLod; ++l)
      for (int shape = 0; shape < (p == static_cast<std::size_t>(PrototypeKind::leaflet) ? kShapeCount : 1);
           ++shape) {
        const auto slot = static_cast<std::size_t>(mesh_slot(static_cast<PrototypeKind>(p), l, shape));
        if (used[slot])
          meshes[slot] = &lib.get(static_cast<PrototypeKind>(p), l, static_cast<std::uint8_t>(shape));
      }
  return meshes;
}

double organ_area(const Stand& stand, std::size_t id, PrototypeLibrary& library) {
  const OrganRecord& r = stand.organs[id];
  return transformed_area(library.get(r), stand.transforms[id]);
}

double organ_length(const Stand& stand, std::size_t id) {
  const auto& p = stand.params[id];
  switch (stand.organs[id].prototype) {
    case PrototypeKind::cylinder:
    case PrototypeKind::leaflet: return p[0];
    case PrototypeKind::sphere:
    case PrototypeKind::disk: return 2.0 * p[0];
  }
  return 0;
}

Vec3f kind_colour(OrganKind k) {
  switch (k) {
    case OrganKind::internode: return {0.30f, 0.45f, 0.15f};
    case OrganKind::petiole: return {0.40f, 0.60f, 0.20f};
    case OrganKind::rachis: return {0.45f, 0.65f, 0.25f};
    case OrganKind::leaflet: return {0.10f, 0.50f, 0.10f};
    case OrganKind::peduncle: return {0.50f, 0.55f, 0.20f};
    case OrganKind::fruit: return {0.80f, 0.10f, 0.05f};
    case OrganKind::flower: return {0.95f, 0.85f, 0.10f};
  }
  return {0.5f, 0.5f, 0.5f};
}

}  // namespace canopy
