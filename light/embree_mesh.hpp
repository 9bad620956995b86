#pragma once
/// A prototype mesh as an Embree scene of one triangle geometry, to be instanced once per organ:
/// the one way canopy light and canopy render put a mesh in Embree.
#include "geometry/prototype.hpp"

#include <embree3/rtcore.h>

#include <algorithm>

namespace canopy::light {

inline RTCScene prototype_scene(RTCDevice dev, const PrototypeMesh& m) {
  RTCScene sc = rtcNewScene(dev);
  RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                        3 * sizeof(float), m.positions.size()));
  for (std::size_t i = 0; i < m.positions.size(); ++i)
    v[3 * i] = m.positions[i].x, v[3 * i + 1] = m.positions[i].y, v[3 * i + 2] = m.positions[i].z;
  auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                             3 * sizeof(unsigned), m.triangle_count()));
  std::copy(m.indices.begin(), m.indices.end(), idx);
  rtcCommitGeometry(g);
  rtcAttachGeometry(sc, g);
  rtcReleaseGeometry(g);
  rtcCommitScene(sc);
  return sc;
}

}  // namespace canopy::light
