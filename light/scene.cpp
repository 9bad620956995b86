#include "light/scene.hpp"

#include "light/embree_mesh.hpp"

#include <embree3/rtcore.h>
#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace canopy::light {

struct Scene::Impl {
  RTCDevice device = nullptr;
  RTCScene top = nullptr;
  std::vector<RTCScene> prototypes;
  ~Impl() {
    if (top) rtcReleaseScene(top);
    for (RTCScene s : prototypes)
      if (s) rtcReleaseScene(s);
    if (device) rtcReleaseDevice(device);
  }
};

namespace {

/// A mesh in its local z = 0 plane: a disk, or a leaflet that is not curved.
bool flat(const OrganRecord& r) {
  return r.prototype == PrototypeKind::disk || (r.prototype == PrototypeKind::leaflet && r.shape == 0);
}

}  // namespace

Scene::Scene(const Stand& s, PrototypeLibrary& lib) : impl_(std::make_unique<Impl>()) {
  // Embree's build threads: as many as the run's OpenMP team (--threads N means N throughout).
  impl_->device = rtcNewDevice(fmt::format("threads={}", std::max(1, omp_get_max_threads())).c_str());
  if (!impl_->device)
    throw std::runtime_error(
        fmt::format("Embree could not start (error {})", static_cast<int>(rtcGetDeviceError(nullptr))));
  RTCDevice dev = impl_->device;
  // One scene per mesh: prototype, level of detail and, for a leaflet, its curved shape.
  impl_->prototypes.assign(kMeshSlots, nullptr);
  const auto proto_scene = [&](const OrganRecord& r) {
    RTCScene& sc = impl_->prototypes[static_cast<std::size_t>(mesh_slot(r.prototype, r.lod, r.shape))];
    if (sc) return sc;
    sc = prototype_scene(dev, lib.get(r));
    return sc;
  };
  impl_->top = rtcNewScene(dev);
  const double inf = std::numeric_limits<double>::infinity();
  lo_ = {inf, inf, inf}, hi_ = {-inf, -inf, -inf};
  for (std::size_t i = 0; i < s.organ_count(); ++i) {
    const OrganRecord& r = s.organs[i];
    Affine3f t = s.transforms[i];
    const Vec3d a = to_double(t.c0), b = to_double(t.c1);
    if (!(std::abs(dot(cross(a, b), to_double(t.c2))) > 0)) {
      // A flat blade lies in its local z = 0 plane, so its third column moves nothing: any
      // column off the blade's plane gives Embree an invertible transform and the same blade.
      const Vec3d n = cross(a, b);
      if (!flat(r) || !(length(n) > 0)) {
        ++skipped_;
        continue;
      }
      t.c2 = to_float(normalized(n) * std::sqrt(length(n)));
    }
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
    RTCGeometry inst = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(inst, proto_scene(r));
    rtcSetGeometryTimeStepCount(inst, 1);
    rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
    rtcCommitGeometry(inst);
    rtcAttachGeometryByID(impl_->top, inst, static_cast<unsigned>(i));
    rtcReleaseGeometry(inst);
    const Box3f& bx = lib.get(r).box;
    for (int k = 0; k < 8; ++k) {
      const Vec3f p = apply(
          t, Vec3f{(k & 1) ? bx.hi.x : bx.lo.x, (k & 2) ? bx.hi.y : bx.lo.y, (k & 4) ? bx.hi.z : bx.lo.z});
      const Vec3d w = to_double(p) + off;
      lo_ = {std::min(lo_.x, w.x), std::min(lo_.y, w.y), std::min(lo_.z, w.z)};
      hi_ = {std::max(hi_.x, w.x), std::max(hi_.y, w.y), std::max(hi_.z, w.z)};
    }
  }
  if (!(lo_.x <= hi_.x)) lo_ = {0, 0, 0}, hi_ = {0, 0, 0};
  // A margin well above float rounding at the stand's extent: the ray's float origin and Embree's
  // float boxes never clip a hit at the box's edge (a wider box only traces a copy more often).
  const double pad =
      1e-5 * (1 + std::max({std::abs(lo_.x), std::abs(lo_.y), std::abs(hi_.x), std::abs(hi_.y), hi_.z}));
  lo_ = lo_ - Vec3d{pad, pad, pad}, hi_ = hi_ + Vec3d{pad, pad, pad};
  lo_.z = std::min(lo_.z, 0.0);
  rtcCommitScene(impl_->top);
  if (rtcGetDeviceError(dev) != RTC_ERROR_NONE)
    throw std::runtime_error("Embree could not build the light scene (out of memory?)");
}

Scene::~Scene() = default;

namespace {

/// Entry and exit of the ray in box [lo, hi] within [0, t_max]; false when it misses.
bool slab(Vec3d o, Vec3d d, Vec3d lo, Vec3d hi, double t_max, double& t0, double& t1) {
  t0 = 0, t1 = t_max;
  const double os[3] = {o.x, o.y, o.z}, ds[3] = {d.x, d.y, d.z}, ls[3] = {lo.x, lo.y, lo.z},
               hs[3] = {hi.x, hi.y, hi.z};
  for (int a = 0; a < 3; ++a) {
    if (ds[a] == 0) {
      if (os[a] < ls[a] || os[a] > hs[a]) return false;
      continue;
    }
    double ta = (ls[a] - os[a]) / ds[a], tb = (hs[a] - os[a]) / ds[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta), t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

}  // namespace

Hit Scene::trace(Vec3d org, Vec3d dir, double t_max) const {
  Hit best;
  best.t = t_max;
  const auto one = [&](Vec3d o, double t0, double t1) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh{};
    rh.ray.org_x = static_cast<float>(o.x), rh.ray.org_y = static_cast<float>(o.y),
    rh.ray.org_z = static_cast<float>(o.z);
    rh.ray.dir_x = static_cast<float>(dir.x), rh.ray.dir_y = static_cast<float>(dir.y),
    rh.ray.dir_z = static_cast<float>(dir.z);
    rh.ray.tnear = static_cast<float>(t0), rh.ray.tfar = static_cast<float>(t1), rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID, rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(impl_->top, &ctx, &rh);
    if (rh.hit.instID[0] != RTC_INVALID_GEOMETRY_ID && rh.ray.tfar < best.t)
      best.organ = rh.hit.instID[0], best.t = rh.ray.tfar;
  };
  if (px_ <= 0 || py_ <= 0) {
    double t0, t1;
    if (slab(org, dir, lo_, hi_, t_max, t0, t1)) one(org, t0, t1);
    return best;
  }
  // The copies of the stand, shifted by (i px, j py), whose boxes the ray's footprint meets.
  const Vec3d end = org + dir * t_max;
  const double sx0 = std::min(org.x, end.x), sx1 = std::max(org.x, end.x), sy0 = std::min(org.y, end.y),
               sy1 = std::max(org.y, end.y);
  const long i0 = static_cast<long>(std::ceil((sx0 - hi_.x) / px_)),
             i1 = static_cast<long>(std::floor((sx1 - lo_.x) / px_));
  const long j0 = static_cast<long>(std::ceil((sy0 - hi_.y) / py_)),
             j1 = static_cast<long>(std::floor((sy1 - lo_.y) / py_));
  struct Copy {
    double t0, t1;
    Vec3d o;
  };
  std::array<Copy, 64> small;
  std::vector<Copy> large;
  std::size_t n = 0;
  const bool many = (i1 - i0 + 1) * (j1 - j0 + 1) > static_cast<long>(small.size());
  for (long i = i0; i <= i1; ++i)
    for (long j = j0; j <= j1; ++j) {
      // The ray in the frame of copy (i, j): its origin moved back by the shift.
      const Vec3d o{org.x - static_cast<double>(i) * px_, org.y - static_cast<double>(j) * py_, org.z};
      double t0, t1;
      if (!slab(o, dir, lo_, hi_, t_max, t0, t1)) continue;
      if (many) large.push_back({t0, t1, o});
      else small[n++] = {t0, t1, o};
    }
  Copy* c = many ? large.data() : small.data();
  if (many) n = large.size();
  std::sort(c, c + n, [](const Copy& a, const Copy& b) { return a.t0 < b.t0; });
  for (std::size_t k = 0; k < n && c[k].t0 < best.t; ++k) one(c[k].o, c[k].t0, std::min(c[k].t1, best.t));
  return best;
}

}  // namespace canopy::light
