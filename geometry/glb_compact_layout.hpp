#pragma once
/// The compact glb's layout of one plant (geometry/export_glb_compact.cpp): its primitives, the
/// node's corner and step, the sizes of its views, and the quantization of its attributes.
#include "geometry/glb_stand.hpp"
#include "geometry/organ_kind.hpp"
#include "geometry/vec.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

namespace canopy::glb_compact {

inline constexpr double kUnits = 65535;  // position steps across a plant's box

struct Primitive {
  OrganKind kind;
  bool uv;
  std::vector<std::uint32_t> organs;
  std::size_t vertices = 0, indices = 0;
  Vec3d lo{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
           std::numeric_limits<double>::max()};
  Vec3d hi{-std::numeric_limits<double>::max(), -std::numeric_limits<double>::max(),
           -std::numeric_limits<double>::max()};
  int index_size() const { return static_cast<int>(glb::index_size_for(vertices)); }
  std::size_t index_bytes() const { return (static_cast<std::size_t>(index_size()) * indices + 3) / 4 * 4; }
};

struct PlantLayout {
  std::vector<Primitive> prims;
  Vec3d corner{0, 0, 0};  // the node's translation
  double step = 0;        // metres per position unit; 0: FLOAT positions (the plant is too large)
  std::size_t vertices = 0, uv_vertices = 0, index_bytes = 0;
  std::size_t stride() const { return step > 0 ? 8 : 16; }  // position, then the id and padding
  std::size_t id_offset() const { return step > 0 ? 6 : 12; }
  std::size_t pos_bytes() const { return stride() * vertices; }
  std::size_t bytes() const { return pos_bytes() + 4 * vertices + 4 * uv_vertices + index_bytes; }
};

// glTF's Y-up frame, relative to the stand origin, in double.
inline Vec3d world(const Vec3d& off, Vec3f v) { return {off.x + v.x, off.z + v.z, -(off.y + v.y)}; }

inline std::uint16_t units(double w, double corner, double step) {
  const double u = std::floor((w - corner) / step + 0.5);
  return static_cast<std::uint16_t>(std::clamp(u, 0.0, kUnits));
}

inline void put_position(char* at, const Vec3d& w, const PlantLayout& L) {
  if (L.step > 0) {
    const std::uint16_t q[3] = {units(w.x, L.corner.x, L.step), units(w.y, L.corner.y, L.step),
                                units(w.z, L.corner.z, L.step)};
    std::memcpy(at, q, 6);
  } else {
    const float f[3] = {static_cast<float>(w.x - L.corner.x), static_cast<float>(w.y - L.corner.y),
                        static_cast<float>(w.z - L.corner.z)};
    std::memcpy(at, f, 12);
  }
}

inline std::int8_t snorm8(float x) {
  return static_cast<std::int8_t>(std::clamp(std::floor(x * 127.0f + 0.5f), -127.0f, 127.0f));
}
inline std::uint16_t unorm16(float x) {
  return static_cast<std::uint16_t>(std::floor(std::clamp(x, 0.0f, 1.0f) * 65535.0f + 0.5f));
}

}  // namespace canopy::glb_compact
