#include "geometry/prototype.hpp"

#include "geometry/leaflet_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace canopy {
namespace {

constexpr double kPi = std::numbers::pi;

// w(s) = N s^a (1 - s)^b with a = 0.5, b = 1: widest at s* = a / (a + b) = 1/3.
constexpr double kBaseExp = 0.5, kTipExp = 1.0;
double leaflet_norm() {
  const double s = kBaseExp / (kBaseExp + kTipExp);
  return 0.5 / (std::pow(s, kBaseExp) * std::pow(1 - s, kTipExp));
}

void finish_box(PrototypeMesh& m) {
  m.corner_lanes.assign((m.triangle_count() + 7) / 8 * PrototypeMesh::kCornerGroupFloats, 0.0f);
  for (std::size_t i = 0; i < m.indices.size(); i += 3) {
    const Vec3f a = m.positions[m.indices[i]], b = m.positions[m.indices[i + 1]],
                c = m.positions[m.indices[i + 2]];
    m.face_cross.push_back(cross(b - a, c - a));
    const std::size_t t = i / 3;
    const float corners[9] = {a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z};
    for (std::size_t k = 0; k < 9; ++k)
      m.corner_lanes[t / 8 * PrototypeMesh::kCornerGroupFloats + 8 * k + t % 8] = corners[k];
  }
  Vec3f lo = m.positions.front(), hi = lo;
  for (const Vec3f& p : m.positions) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  m.box = {lo, hi};
}

void tri(PrototypeMesh& m, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  m.indices.insert(m.indices.end(), {a, b, c});
}

std::uint32_t vertex(PrototypeMesh& m, Vec3f p, Vec3f n) {
  m.positions.push_back(p);
  m.normals.push_back(n);
  return static_cast<std::uint32_t>(m.positions.size() - 1);
}

PrototypeMesh leaflet(int lod) {
  PrototypeMesh m;
  const int n = 4 * lod + 1;  // segments along the midrib
  const Vec3f up{0, 0, 1};
  // Stations at s = t^2 so the sqrt-shaped base is sampled as finely as the tip.
  std::vector<std::uint32_t> left, right;
  const std::uint32_t base = vertex(m, {0, 0, 0}, up);
  m.uvs.push_back({0, 0.5f});
  for (int i = 1; i < n; ++i) {
    const double t = static_cast<double>(i) / n;
    const double s = t * t;
    const float w = static_cast<float>(leaflet_half_width(s));
    left.push_back(vertex(m, {static_cast<float>(s), w, 0}, up));
    m.uvs.push_back({static_cast<float>(s), 0.5f + w});
    right.push_back(vertex(m, {static_cast<float>(s), -w, 0}, up));
    m.uvs.push_back({static_cast<float>(s), 0.5f - w});
  }
  const std::uint32_t tip = vertex(m, {1, 0, 0}, up);
  m.uvs.push_back({1, 0.5f});
  // Counter-clockwise seen from +z: x forward, y to the left.
  tri(m, base, right[0], left[0]);
  for (int i = 0; i + 1 < n - 1; ++i) {
    tri(m, left[i], right[i], right[i + 1]);
    tri(m, left[i], right[i + 1], left[i + 1]);
  }
  tri(m, left.back(), right.back(), tip);
  return m;
}

PrototypeMesh cylinder(int lod) {
  PrototypeMesh m;
  const int k = 4 * lod;
  std::vector<std::uint32_t> lo, hi;
  for (int i = 0; i < k; ++i) {
    const double a = 2 * kPi * i / k;
    const Vec3f radial{0, static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a))};
    lo.push_back(vertex(m, {0, radial.y, radial.z}, radial));
    hi.push_back(vertex(m, {1, radial.y, radial.z}, radial));
  }
  for (int i = 0; i < k; ++i) {
    const int j = (i + 1) % k;
    tri(m, lo[i], lo[j], hi[j]);
    tri(m, lo[i], hi[j], hi[i]);
  }
  // Caps with their own flat normals, fanned from their first vertex.
  std::vector<std::uint32_t> c0, c1;
  for (int i = 0; i < k; ++i) {
    c0.push_back(vertex(m, m.positions[lo[i]], {-1, 0, 0}));
    c1.push_back(vertex(m, m.positions[hi[i]], {1, 0, 0}));
  }
  for (int i = 1; i + 1 < k; ++i) {
    tri(m, c0[0], c0[i + 1], c0[i]);
    tri(m, c1[0], c1[i], c1[i + 1]);
  }
  return m;
}

PrototypeMesh sphere(int lod) {
  PrototypeMesh m;
  const int lon = 4 * lod, bands = 2 * lod + 1;
  const Vec3f centre{1, 0, 0};
  // Poles on the x axis (the heading), rings between them.
  const std::uint32_t back = vertex(m, {0, 0, 0}, {-1, 0, 0});
  std::vector<std::vector<std::uint32_t>> rings;
  for (int b = 1; b < bands; ++b) {
    const double th = kPi * b / bands;
    std::vector<std::uint32_t> ring;
    for (int i = 0; i < lon; ++i) {
      const double ph = 2 * kPi * i / lon;
      const Vec3f n{static_cast<float>(-std::cos(th)), static_cast<float>(std::sin(th) * std::cos(ph)),
                    static_cast<float>(std::sin(th) * std::sin(ph))};
      ring.push_back(vertex(m, centre + n, n));
    }
    rings.push_back(ring);
  }
  const std::uint32_t front = vertex(m, {2, 0, 0}, {1, 0, 0});
  for (int i = 0; i < lon; ++i) {
    const int j = (i + 1) % lon;
    tri(m, back, rings.front()[j], rings.front()[i]);
    for (std::size_t r = 0; r + 1 < rings.size(); ++r) {
      tri(m, rings[r][i], rings[r][j], rings[r + 1][j]);
      tri(m, rings[r][i], rings[r + 1][j], rings[r + 1][i]);
    }
    tri(m, rings.back()[i], rings.back()[j], front);
  }
  return m;
}

PrototypeMesh disk(int lod) {
  PrototypeMesh m;
  const int k = 8 * lod;
  for (int i = 0; i < k; ++i) {
    const double a = 2 * kPi * i / k;
    vertex(m, {static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)), 0}, {0, 0, 1});
  }
  for (int i = 1; i + 1 < k; ++i) tri(m, 0, static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(i + 1));
  return m;
}

}  // namespace

double leaflet_half_width(double s) {
  if (s <= 0 || s >= 1) return 0;
  return leaflet_norm() * std::pow(s, kBaseExp) * std::pow(1 - s, kTipExp);
}

double leaflet_outline_area() {
  // 2 N B(a+1, b+1), the Beta function by its Gamma form.
  const double beta =
      std::tgamma(kBaseExp + 1) * std::tgamma(kTipExp + 1) / std::tgamma(kBaseExp + kTipExp + 2);
  return 2 * leaflet_norm() * beta;
}

PrototypeMesh make_prototype(PrototypeKind kind, int lod, std::uint8_t shape) {
  if (lod < 1 || lod > kMaxLod) throw std::invalid_argument("level of detail must lie in 1..16");
  if (shape != 0 && kind != PrototypeKind::leaflet)
    throw std::invalid_argument(std::string("a ") + std::string(name_of(kind)) +
                                " has no shape (only leaflets curve)");
  PrototypeMesh m;
  switch (kind) {
    case PrototypeKind::cylinder: m = cylinder(lod); break;
    case PrototypeKind::leaflet: m = shape ? curved_leaflet(lod, leaflet_shape(shape)) : leaflet(lod); break;
    case PrototypeKind::sphere: m = sphere(lod); break;
    case PrototypeKind::disk: m = disk(lod); break;
  }
  finish_box(m);
  return m;
}

const PrototypeMesh& PrototypeLibrary::make(PrototypeKind kind, int lod, std::uint8_t shape) {
  if (lod < 1 || lod > kMaxLod) throw std::invalid_argument("level of detail must lie in 1..16");
  if (shape != 0 && kind != PrototypeKind::leaflet)
    throw std::invalid_argument(std::string("a ") + std::string(name_of(kind)) +
                                " has no shape (only leaflets curve)");
  auto& slot = made_[static_cast<std::size_t>(mesh_slot(kind, lod, shape))];
  std::lock_guard<std::mutex> lock(mutex_);
  if (const PrototypeMesh* m = slot.load(std::memory_order_relaxed)) return *m;
  owned_.push_back(std::make_unique<PrototypeMesh>(make_prototype(kind, lod, shape)));
  slot.store(owned_.back().get(), std::memory_order_release);
  return *owned_.back();
}

double transformed_area(const PrototypeMesh& m, const Affine3f& t) {
  // A u x A v = cof(A) (u x v): one cofactor matrix per organ, one product per triangle.
  const Vec3d c0 = to_double(t.c0), c1 = to_double(t.c1), c2 = to_double(t.c2);
  const Vec3d k0 = cross(c1, c2), k1 = cross(c2, c0), k2 = cross(c0, c1);
  double area = 0;
  for (const Vec3f& f : m.face_cross) area += 0.5 * length(k0 * f.x + k1 * f.y + k2 * f.z);
  return area;
}

}  // namespace canopy
