#include "light/scene.hpp"

#include "geometry/clock.hpp"
#include "light/embree_stand.hpp"
#include "light/raster_stand.hpp"

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
  EmbreeStand embree;
  Impl(const Stand& s, PrototypeLibrary& lib) : embree(s, lib) {}
};

Scene::Scene(const Stand& s, PrototypeLibrary& lib) : stand_(s), lib_(lib) {
  if (!stand_box(s, lib, lo_, hi_, skipped_)) lo_ = {0, 0, 0}, hi_ = {0, 0, 0};
  // A margin well above float rounding at the stand's extent: the ray's float origin and Embree's
  // float boxes never clip a hit at the box's edge (a wider box only traces a copy more often).
  const double pad =
      1e-5 * (1 + std::max({std::abs(lo_.x), std::abs(lo_.y), std::abs(hi_.x), std::abs(hi_.y), hi_.z}));
  lo_ = lo_ - Vec3d{pad, pad, pad}, hi_ = hi_ + Vec3d{pad, pad, pad};
  lo_.z = std::min(lo_.z, 0.0);
}

Scene::~Scene() = default;

void Scene::build() {
  if (impl_) return;
  const auto t0 = std::chrono::steady_clock::now();
  impl_ = std::make_unique<Impl>(stand_, lib_);
  build_s_ = seconds_since(t0);
}

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
    rtcIntersect1(impl_->embree.scene(), &ctx, &rh);
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
