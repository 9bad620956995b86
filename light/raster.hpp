#pragma once
/// Light by rasterization: the rays of a direction's jittered grid (light/sampler.hpp: one ray per
/// cell, at the cell's hashed point) answered by projecting every triangle of the stand along the
/// direction onto the ground and keeping, per cell, the highest triangle over the cell's point.
/// A ray comes down from the sky, so the highest point it crosses is its first hit: the cell's
/// answer is the one the ray caster gives, for a cost that grows with the triangles rather than
/// with the rays (a hundred million rays cost little more than a million). Periodic fields wrap
/// the projected triangle around the tile, which is what tracing every shifted copy of the stand
/// does.
///
/// Both the host (light/raster_stand.cpp) and the device (cuda/light_raster.cu) run these
/// functions, so a cell's answer is the same bits on either.
#include "geometry/hd.hpp"
#include "geometry/mix64.hpp"
#include "geometry/vec.hpp"
#include "light/tally.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace canopy::light {

/// One direction's grid as the rasterizer reads it (what trace_direction draws).
struct RasterGrid {
  double x0 = 0, y0 = 0, cw = 1, ch = 1;  // the region's corner and the cell size, metres
  std::int64_t nx = 2, ny = 1;
  std::uint64_t base = 0;  // the direction's hash of cell points
  double kx = 0, ky = 0;   // ground shift per metre of height: -toward.x / toward.z, -toward.y / toward.z
  bool periodic = true;    // cells wrap around the region (the tile)
};

/// The meshes and organs to draw: per mesh slot its triangles (indices into its own vertices),
/// per organ its transform into the plant frame, its slot (-1: left out) and its plant.
struct RasterView {
  const Vec3f* positions = nullptr;  // every mesh's vertices, one mesh after another
  const std::uint32_t* indices = nullptr;
  const std::uint32_t* slot_tri_first = nullptr;  // per slot: first triangle (in triangles of `indices`)
  const std::uint32_t* slot_tri_count = nullptr;
  const std::uint32_t* slot_vertex_first = nullptr;
  const Affine3f* transforms = nullptr;  // per organ, plant frame
  const std::int16_t* slot = nullptr;    // per organ
  const std::int32_t* plant = nullptr;   // per organ
  const std::uint8_t* kind = nullptr;    // per organ (OrganKind)
  const Vec3d* offset = nullptr;         // per plant, relative to stand_origin
  std::uint64_t organs = 0, plants = 0, vertices = 0, mesh_triangles = 0, slots = 0;
  /// Unique to the RasterStand the view is of (a device keeps what it uploaded for it).
  std::uint64_t generation = 0;
};

CANOPY_HD inline double unit_interval(std::uint64_t h) { return static_cast<double>(h >> 11) * 0x1.0p-53; }

/// The ground point (x, y) of cell (i, j)'s ray.
CANOPY_HD inline void cell_point(const RasterGrid& g, std::uint64_t i, std::uint64_t j, double& x,
                                 double& y) {
  const std::uint64_t h = mix64(g.base ^ mix64(j * kGoldenGamma ^ mix64(i)));
  x = g.x0 + (static_cast<double>(i) + unit_interval(h)) * g.cw;
  y = g.y0 + (static_cast<double>(j) + unit_interval(mix64(h))) * g.ch;
}

/// A cell's answer as one number whose maximum is the first hit: the hit's height (float bits,
/// ordered as the heights are for z >= 0) above the organ's index + 1; 0 is no hit.
CANOPY_HD inline std::uint64_t hit_key(double z, std::uint32_t organ) {
  const float f = static_cast<float>(z);
#ifdef __CUDA_ARCH__
  const std::uint32_t bits = __float_as_uint(f);
#else
  std::uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
#endif
  return static_cast<std::uint64_t>(bits) << 32 | (static_cast<std::uint64_t>(organ) + 1);
}
CANOPY_HD inline std::int64_t key_organ(std::uint64_t key) {
  return static_cast<std::int64_t>(key & 0xffffffffu) - 1;
}
CANOPY_HD inline float key_height(std::uint64_t key) {
  const auto bits = static_cast<std::uint32_t>(key >> 32);
#ifdef __CUDA_ARCH__
  return __uint_as_float(bits);
#else
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
#endif
}

CANOPY_HD inline std::int64_t floor_to_int(double v) {
  const auto i = static_cast<std::int64_t>(v);
  return static_cast<double>(i) > v ? i - 1 : i;
}
CANOPY_HD inline std::int64_t wrap(std::int64_t i, std::int64_t n) {
  const std::int64_t r = i % n;
  return r < 0 ? r + n : r;
}

/// The profile's layer of a hit at height z (layers of `layer_m` from the ground, the last open).
CANOPY_HD inline std::int32_t layer_of(double z, double layer_m, std::int32_t layers) {
  const double f = floor(z / layer_m);
  const std::int32_t l = f < 0 ? 0 : f >= layers ? layers - 1 : static_cast<std::int32_t>(f);
  return l;
}

/// What a hit of `organ` at height z counts as (organ < 0: no hit).
CANOPY_HD inline Outcome hit_outcome(std::int64_t organ, double z, const std::int32_t* plant,
                                     const std::uint8_t* kind, double layer_m, std::int32_t layers) {
  Outcome o;
  if (organ < 0) return o;
  o.plant = plant[organ];
  o.kind = kind[organ];
  o.leaflet = o.kind == static_cast<std::uint8_t>(OrganKind::leaflet);
  o.layer = layer_of(z, layer_m, layers);
  return o;
}

/// Draws the triangle (world points relative to stand_origin, metres): `put(cell, key)` for every
/// cell whose ray crosses it above the ground, key = hit_key(height there, organ).
template <class Put>
CANOPY_HD inline void raster_triangle(const RasterGrid& g, const Vec3d p[3], std::uint32_t organ, Put& put) {
  double gx[3], gy[3];
  for (int k = 0; k < 3; ++k) gx[k] = p[k].x + p[k].z * g.kx, gy[k] = p[k].y + p[k].z * g.ky;
  const double area2 = (gx[1] - gx[0]) * (gy[2] - gy[0]) - (gx[2] - gx[0]) * (gy[1] - gy[0]);
  if (!(area2 != 0)) return;  // seen edge-on (or not a number): no ray crosses it
  const double lo_x = fmin(gx[0], fmin(gx[1], gx[2])), hi_x = fmax(gx[0], fmax(gx[1], gx[2]));
  const double lo_y = fmin(gy[0], fmin(gy[1], gy[2])), hi_y = fmax(gy[0], fmax(gy[1], gy[2]));
  std::int64_t i0 = floor_to_int((lo_x - g.x0) / g.cw), i1 = floor_to_int((hi_x - g.x0) / g.cw);
  std::int64_t j0 = floor_to_int((lo_y - g.y0) / g.ch), j1 = floor_to_int((hi_y - g.y0) / g.ch);
  if (!g.periodic) {
    i0 = i0 < 0 ? 0 : i0, j0 = j0 < 0 ? 0 : j0;
    i1 = i1 >= g.nx ? g.nx - 1 : i1, j1 = j1 >= g.ny ? g.ny - 1 : j1;
  }
  const double inv = 1 / area2;
  // The wrapped indices advance with the unwrapped ones (one modulo per triangle, not per cell).
  std::int64_t j = g.periodic ? wrap(j0, g.ny) : j0;
  for (std::int64_t jj = j0; jj <= j1; ++jj) {
    std::int64_t i = g.periodic ? wrap(i0, g.nx) : i0;
    for (std::int64_t ii = i0; ii <= i1; ++ii) {
      double x, y;
      cell_point(g, static_cast<std::uint64_t>(i), static_cast<std::uint64_t>(j), x, y);
      x += static_cast<double>(ii - i) * g.cw, y += static_cast<double>(jj - j) * g.ch;  // the copy's point
      const double w0 = ((gx[1] - x) * (gy[2] - y) - (gx[2] - x) * (gy[1] - y)) * inv;
      const double w1 = ((gx[2] - x) * (gy[0] - y) - (gx[0] - x) * (gy[2] - y)) * inv;
      const double w2 = 1 - w0 - w1;
      if (w0 >= 0 && w1 >= 0 && w2 >= 0) {
        const double z = w0 * p[0].z + w1 * p[1].z + w2 * p[2].z;
        if (z >= 0)  // below the ground the ray has ended
          put(static_cast<std::uint64_t>(j) * static_cast<std::uint64_t>(g.nx) +
                  static_cast<std::uint64_t>(i),
              hit_key(z, organ));
      }
      if (++i == g.nx && g.periodic) i = 0;
    }
    if (++j == g.ny && g.periodic) j = 0;
  }
}

/// Draws every triangle of organ `o`.
template <class Put>
CANOPY_HD inline void raster_organ(const RasterGrid& g, const RasterView& v, std::uint64_t o, Put& put) {
  const int slot = v.slot[o];
  if (slot < 0) return;
  const Affine3f& t = v.transforms[o];
  const Vec3d off = v.offset[v.plant[o]];
  const std::uint32_t first = v.slot_tri_first[slot], n = v.slot_tri_count[slot];
  const Vec3f* pos = v.positions + v.slot_vertex_first[slot];
  for (std::uint32_t k = 0; k < n; ++k) {
    const std::uint32_t* tri = v.indices + 3 * static_cast<std::uint64_t>(first + k);
    Vec3d p[3];
    for (int c = 0; c < 3; ++c) {
      const Vec3f w = apply(t, pos[tri[c]]);
      p[c] = Vec3d{static_cast<double>(w.x) + off.x, static_cast<double>(w.y) + off.y,
                   static_cast<double>(w.z) + off.z};
    }
    raster_triangle(g, p, static_cast<std::uint32_t>(o), put);
  }
}

}  // namespace canopy::light
