// canopy render's pictures: on a hand-built stand, the pixels where a highlighted (contact)
// organ was placed are magenta, an organ that is not highlighted shows its kind's colour, and the
// PNG written reads back the same.
#include "geometry/organ_mesh.hpp"
#include "tools/render/scene.hpp"

#include <doctest/doctest.h>

#include <cstdio>
#include <filesystem>

using namespace canopy;

namespace {

/// A plant at (x, 0) with one leaflet-kind disk of radius r lying flat at height z.
void add_disk_plant(Stand& s, double x, float r, float z, OrganKind kind) {
  PlantRecord p;
  p.x = x;
  p.first_organ = static_cast<std::uint32_t>(s.organ_count());
  OrganRecord o;
  o.plant = static_cast<std::int32_t>(s.plant_count());
  o.kind = kind;
  o.prototype = PrototypeKind::disk;
  o.lod = 4;
  Affine3f t;
  t.c0 = {r, 0, 0}, t.c1 = {0, r, 0}, t.c2 = {0, 0, r}, t.t = {0, 0, z};
  s.organs.push_back(o), s.transforms.push_back(t), s.params.push_back({r, 0}),
      s.joint_limit_deg.push_back(60);
  p.organ_count = 1;
  s.plants.push_back(p);
}

}  // namespace

TEST_CASE("render: contact organs magenta where they were placed, others in their kind's colour") {
  Stand s;
  add_disk_plant(s, 0.0, 0.1f, 0.5f, OrganKind::leaflet);  // organ 0: in contact
  add_disk_plant(s, 1.0, 0.1f, 0.5f, OrganKind::leaflet);  // organ 1: not
  add_disk_plant(s, 2.0, 0.1f, 0.5f, OrganKind::fruit);    // organ 2: not, another kind
  PrototypeLibrary lib;
  const render::Scene scene(s, lib);
  const render::Camera cam = render::fit_camera(scene.lo(), scene.hi(), render::View::top, 400, 200);
  const render::Image img = scene.render(cam, {1, 0, 0});
  const auto pixel = [&](double x, double y, double z) {
    double col = 0, row = 0;
    cam.project({x, y, z}, col, row);
    REQUIRE(col >= 0);
    REQUIRE(col < img.width);
    REQUIRE(row >= 0);
    REQUIRE(row < img.height);
    return img.at(static_cast<int>(col), static_cast<int>(row));
  };
  const std::uint8_t* hot = pixel(0, 0, 0.5);
  CHECK(hot[0] > 200);
  CHECK(hot[1] < 40);
  CHECK(hot[2] > 170);
  // Lambert-shaded kind colours: the hue of leaflet green and fruit red.
  const std::uint8_t* leaf = pixel(1, 0, 0.5);
  CHECK(leaf[1] > leaf[0] + 40);
  CHECK(leaf[1] > leaf[2] + 40);
  const std::uint8_t* fruit = pixel(2, 0, 0.5);
  CHECK(fruit[0] > fruit[1] + 80);
  // Between the disks: the soil, not an organ.
  const std::uint8_t* soil = pixel(0.5, 0, 0);
  CHECK(soil[0] > soil[2]);
  CHECK_FALSE((soil[0] > 200 && soil[1] < 40));
  // The same picture from a camera with the organs moved: nothing is magenta without highlights.
  const render::Image plain = scene.render(cam, {});
  std::size_t magenta = 0;
  for (int y = 0; y < plain.height; ++y)
    for (int x = 0; x < plain.width; ++x)
      magenta += plain.at(x, y)[0] > 200 && plain.at(x, y)[1] < 40 && plain.at(x, y)[2] > 170;
  CHECK(magenta == 0);
  // PNG round trip.
  const std::string path = (std::filesystem::temp_directory_path() / "canopy_test_render.png").string();
  render::write_png(img, path);
  const render::Image back = render::read_png(path);
  CHECK(back.width == img.width);
  CHECK(back.height == img.height);
  CHECK(back.rgb == img.rgb);
  // A picture that cannot be written whole fails and leaves the one before it: /dev/full takes
  // no byte (it exited 0 saying "wrote"), and a PNG is never written in place.
  CHECK_THROWS(render::write_png(plain, "/dev/full"));
  render::write_png(plain, path);
  CHECK(render::read_png(path).rgb == plain.rgb);
  for (const auto& e : std::filesystem::directory_iterator(std::filesystem::temp_directory_path()))
    CHECK(e.path().filename().string().find("canopy_test_render.png.tmp-") == std::string::npos);
  std::remove(path.c_str());
}
