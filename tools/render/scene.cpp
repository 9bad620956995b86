#include "tools/render/scene.hpp"

#include "geometry/organ_mesh.hpp"

#include "light/embree_stand.hpp"
#include "light/raster_stand.hpp"

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
  light::EmbreeStand embree;
  Impl(const Stand& s, PrototypeLibrary& lib) : embree(s, lib) {}
};

Scene::Scene(const Stand& s, PrototypeLibrary& lib) : impl_(std::make_unique<Impl>(s, lib)), stand_(s) {
  std::size_t left_out = 0;
  if (!light::stand_box(s, lib, lo_, hi_, left_out)) lo_ = {-0.5, -0.5, 0}, hi_ = {0.5, 0.5, 1};
  lo_.z = std::min(lo_.z, 0.0);
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
      rtcIntersect1(impl_->embree.scene(), &ctx, &rh);
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
