#include "light/embree_stand.hpp"

#include "light/raster_stand.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace canopy::light {
namespace {

RTCScene mesh_scene(RTCDevice dev, const PrototypeMesh& m) {
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

}  // namespace

EmbreeStand::EmbreeStand(const Stand& s, PrototypeLibrary& lib) {
  device_ = rtcNewDevice(fmt::format("threads={}", std::max(1, omp_get_max_threads())).c_str());
  if (!device_) {
    const RTCError e = rtcGetDeviceError(nullptr);
    // Embree's codes (rtcore_device.h): out of memory is what a user can act on.
    if (e == RTC_ERROR_OUT_OF_MEMORY)
      throw std::runtime_error(
          "the ray tracer (Embree) could not start: out of memory (under `ulimit -v`, its threads' stacks "
          "count too; give it more memory or fewer --threads)");
    throw std::runtime_error(
        fmt::format("the ray tracer (Embree) could not start (Embree error {})", static_cast<int>(e)));
  }
  try {
    build(s, lib);
  } catch (...) {
    release();  // a constructor that throws runs no destructor
    throw;
  }
}

void EmbreeStand::build(const Stand& s, PrototypeLibrary& lib) {
  meshes_.assign(kMeshSlots, nullptr);
  top_ = rtcNewScene(device_);
  for (std::size_t i = 0; i < s.organ_count(); ++i) {
    const OrganRecord& r = s.organs[i];
    Affine3f t = s.transforms[i];
    if (left_out(r, t)) continue;
    const Vec3d a = to_double(t.c0), b = to_double(t.c1);
    if (!(std::abs(dot(cross(a, b), to_double(t.c2))) > 0)) {
      // A flat blade lies in its local z = 0 plane, so its third column moves nothing: any
      // column off the blade's plane gives Embree an invertible transform and the same blade.
      const Vec3d n = cross(a, b);
      t.c2 = to_float(normalized(n) * std::sqrt(length(n)));
    }
    RTCScene& mesh = meshes_[static_cast<std::size_t>(mesh_slot(r.prototype, r.lod, r.shape))];
    if (!mesh) mesh = mesh_scene(device_, lib.get(r));
    const Vec3d off = s.offset(static_cast<std::size_t>(r.plant));
    const float xfm[12] = {t.c0.x,
                           t.c0.y,
                           t.c0.z,
                           t.c1.x,
                           t.c1.y,
                           t.c1.z,
                           t.c2.x,
                           t.c2.y,
                           t.c2.z,
                           static_cast<float>(t.t.x + off.x),
                           static_cast<float>(t.t.y + off.y),
                           static_cast<float>(t.t.z + off.z)};
    RTCGeometry inst = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(inst, mesh);
    rtcSetGeometryTimeStepCount(inst, 1);
    rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
    rtcCommitGeometry(inst);
    rtcAttachGeometryByID(top_, inst, static_cast<unsigned>(i));
    rtcReleaseGeometry(inst);
  }
  rtcCommitScene(top_);
  if (rtcGetDeviceError(device_) != RTC_ERROR_NONE)
    throw std::runtime_error("Embree could not build the scene (out of memory?)");
}

void EmbreeStand::release() {
  if (top_) rtcReleaseScene(top_);
  for (RTCScene sc : meshes_)
    if (sc) rtcReleaseScene(sc);
  if (device_) rtcReleaseDevice(device_);
  top_ = nullptr, meshes_.clear(), device_ = nullptr;
}

}  // namespace canopy::light
