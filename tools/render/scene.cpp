#include "tools/render/scene.hpp"

#include "geometry/organ_mesh.hpp"

#include "light/embree_mesh.hpp"

#include <embree3/rtcore.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace canopy::render {

void Camera::project(Vec3d p, double& col, double& row) const {
  const Vec3d q = p - centre;
  col = (dot(q, right) / half_w * 0.5 + 0.5) * width;
  row = (0.5 - dot(q, up) / half_h * 0.5) * height;
}

Camera fit_camera(Vec3d lo, Vec3d hi, View view, int width, int height) {
  Camera c;
  c.width = width, c.height = height;
  c.centre = (lo + hi) * 0.5;
  c.dir = view == View::top    ? Vec3d{0, 0, -1}
          : view == View::side ? Vec3d{0, 1, 0}
                               : normalized(Vec3d{0.45, 1.0, -0.75});
  c.right = view == View::top ? Vec3d{1, 0, 0} : normalized(cross(c.dir, Vec3d{0, 0, 1}));
  c.up = cross(c.right, c.dir);
  double mu = 1e-6, mv = 1e-6;
  for (int i = 0; i < 8; ++i) {
    const Vec3d p{(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z};
    mu = std::max(mu, std::abs(dot(p - c.centre, c.right)));
    mv = std::max(mv, std::abs(dot(p - c.centre, c.up)));
  }
  mu *= 1.04, mv *= 1.04;
  const double aspect = static_cast<double>(width) / height;
  if (mu / mv < aspect) mu = mv * aspect;
  else mv = mu / aspect;
  c.half_w = mu, c.half_h = mv;
  c.back = length(hi - lo) + 1;
  return c;
}

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

Scene::Scene(const Stand& s, PrototypeLibrary& lib) : impl_(std::make_unique<Impl>()), stand_(s) {
  impl_->device = rtcNewDevice(nullptr);
  if (!impl_->device)
    throw std::runtime_error(
        fmt::format("Embree could not start (error {})", static_cast<int>(rtcGetDeviceError(nullptr))));
  RTCDevice dev = impl_->device;
  impl_->prototypes.assign(kMeshSlots, nullptr);
  const auto proto_scene = [&](const OrganRecord& r) {
    RTCScene& sc = impl_->prototypes[static_cast<std::size_t>(mesh_slot(r.prototype, r.lod, r.shape))];
    if (sc) return sc;
    sc = light::prototype_scene(dev, lib.get(r));
    return sc;
  };
  impl_->top = rtcNewScene(dev);
  const double inf = std::numeric_limits<double>::infinity();
  lo_ = {inf, inf, inf}, hi_ = {-inf, -inf, -inf};
  for (std::size_t i = 0; i < s.organ_count(); ++i) {
    const OrganRecord& r = s.organs[i];
    const Affine3f& t = s.transforms[i];
    const Vec3d det3 = cross(to_double(t.c0), to_double(t.c1));
    if (!(std::abs(dot(det3, to_double(t.c2))) > 0)) continue;  // a flat or empty organ shows nothing
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
    const Box3f& b = lib.get(r).box;
    for (int k = 0; k < 8; ++k) {
      const Vec3f p =
          apply(t, Vec3f{(k & 1) ? b.hi.x : b.lo.x, (k & 2) ? b.hi.y : b.lo.y, (k & 4) ? b.hi.z : b.lo.z});
      const Vec3d w = to_double(p) + off;
      lo_ = {std::min(lo_.x, w.x), std::min(lo_.y, w.y), std::min(lo_.z, w.z)};
      hi_ = {std::max(hi_.x, w.x), std::max(hi_.y, w.y), std::max(hi_.z, w.z)};
    }
  }
  if (!(lo_.x <= hi_.x)) lo_ = {-0.5, -0.5, 0}, hi_ = {0.5, 0.5, 1};
  lo_.z = std::min(lo_.z, 0.0);
  rtcCommitScene(impl_->top);
  if (rtcGetDeviceError(dev) != RTC_ERROR_NONE)
    throw std::runtime_error("Embree could not build the scene (out of memory?)");
}

Scene::~Scene() = default;

Image Scene::render(const Camera& cam, const std::vector<std::uint8_t>& highlight) const {
  Image img(cam.width, cam.height);
  const Vec3d light = normalized(Vec3d{0.3, -0.4, 0.85});
  const float sky[3] = {0.86f, 0.90f, 0.95f}, soil[3] = {0.56f, 0.47f, 0.38f};
  const double ground = lo_.z;
  // The soil: the stand's footprint and a margin of a fifth of its size around it.
  const double mx = 0.2 * (hi_.x - lo_.x) + 0.2, my = 0.2 * (hi_.y - lo_.y) + 0.2;
  const auto on_soil = [&](Vec3d p) {
    return p.x > lo_.x - mx && p.x < hi_.x + mx && p.y > lo_.y - my && p.y < hi_.y + my;
  };
#pragma omp parallel for schedule(dynamic, 4)
  for (int y = 0; y < cam.height; ++y) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    for (int x = 0; x < cam.width; ++x) {
      const double u = ((x + 0.5) / cam.width * 2 - 1) * cam.half_w,
                   v = (1 - (y + 0.5) / cam.height * 2) * cam.half_h;
      const Vec3d org = cam.centre + cam.right * u + cam.up * v - cam.dir * cam.back;
      RTCRayHit rh{};
      rh.ray.org_x = static_cast<float>(org.x), rh.ray.org_y = static_cast<float>(org.y),
      rh.ray.org_z = static_cast<float>(org.z);
      rh.ray.dir_x = static_cast<float>(cam.dir.x), rh.ray.dir_y = static_cast<float>(cam.dir.y),
      rh.ray.dir_z = static_cast<float>(cam.dir.z);
      rh.ray.tnear = 0, rh.ray.tfar = std::numeric_limits<float>::infinity(), rh.ray.mask = 0xffffffffu;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID, rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(impl_->top, &ctx, &rh);
      float c[3];
      if (rh.hit.instID[0] != RTC_INVALID_GEOMETRY_ID) {
        const std::size_t organ = rh.hit.instID[0];
        const Affine3f& t = stand_.transforms[organ];
        // The object-space normal carried to the world by the cofactor matrix of the transform.
        const Vec3d a = to_double(t.c0), b = to_double(t.c1), d = to_double(t.c2);
        const Vec3d n =
            normalized(cross(b, d) * rh.hit.Ng_x + cross(d, a) * rh.hit.Ng_y + cross(a, b) * rh.hit.Ng_z);
        const double shade = 0.35 + 0.65 * std::abs(dot(n, light));
        const bool hot = organ < highlight.size() && highlight[organ];
        const Vec3f k = kind_colour(stand_.organs[organ].kind);
        const float base[3] = {hot ? kContactColour[0] : k.x, hot ? kContactColour[1] : k.y,
                               hot ? kContactColour[2] : k.z};
        for (int i = 0; i < 3; ++i) c[i] = static_cast<float>(base[i] * (hot ? std::max(shade, 0.8) : shade));
      } else if (cam.dir.z < 0 && org.z > ground && on_soil(org + cam.dir * ((ground - org.z) / cam.dir.z))) {
        for (int i = 0; i < 3; ++i) c[i] = soil[i];
      } else {
        for (int i = 0; i < 3; ++i) c[i] = sky[i];
      }
      std::uint8_t* px = img.at(x, y);
      for (int i = 0; i < 3; ++i)
        px[i] = static_cast<std::uint8_t>(std::lround(std::clamp(c[i], 0.0f, 1.0f) * 255));
    }
  }
  return img;
}

}  // namespace canopy::render
