// The GPU's drawing and counting of light's cells against the host's: the same counts, field by
// field, for seeded stands, periodic and isolated, sun high and low, and a canopy light run with
// a GPU against the same run on the host's threads.
#include "cuda/light_raster.hpp"
#include "geometry/layout.hpp"
#include "light/light.hpp"
#include "light/raster_stand.hpp"
#include "lsystem/grow.hpp"

#include <doctest/doctest.h>

#include <string>
#include <vector>

using namespace canopy;

namespace {

Stand tomato_rows(int rows, int per_row, std::uint64_t seed) {
  GrowRequest req;
  req.grammar = std::string(CANOPY_SOURCE_DIR) + "/grammars/tomato.yaml";
  RowLayout layout;
  layout.rows = rows, layout.per_row = per_row, layout.random_rotation = true, layout.jitter = 0.02;
  layout.seed = seed;
  req.plants = row_layout(layout);
  return grow_stand(req);
}

void same(const light::Tally& a, const light::Tally& b) {
  CHECK(a.rays == b.rays);
  CHECK(a.hits == b.hits);
  CHECK(a.hits_diff == b.hits_diff);
  CHECK(a.leaf == b.leaf);
  CHECK(a.leaf_diff == b.leaf_diff);
  CHECK(a.kind == b.kind);
  CHECK(a.kind_diff == b.kind_diff);
  CHECK(a.plant == b.plant);
  CHECK(a.plant_diff == b.plant_diff);
  CHECK(a.plant_leaf == b.plant_leaf);
  CHECK(a.plant_leaf_diff == b.plant_leaf_diff);
  CHECK(a.layer == b.layer);
  CHECK(a.layer_diff == b.layer_diff);
}

}  // namespace

TEST_CASE("light raster: the GPU counts every field as the host does") {
  // One device for two stands in turn (each uploaded for its own RasterStand), layers counted in
  // a block's shared memory (20) and in global memory (600).
  cuda::LightRaster gpu(0);
  for (std::uint64_t seed : {5u, 6u, 5u}) {
    const Stand s = tomato_rows(3, 8, seed);
    PrototypeLibrary lib;
    const light::OrganIndex organs(s);
    const light::RasterStand raster(s, lib, organs);
    const light::Box2d tile{-0.2, -0.5, 3.0, 2.5};
    std::uint64_t stream = seed;
    for (const light::Beam b : std::vector<light::Beam>{{90, 0}, {50, 140}, {12, 300}})
      for (bool periodic : {true, false})
        for (double rays : {3e3, 4e5})
          for (std::size_t layers : {20u, 600u}) {
            light::DirectionJob job;
            job.toward = light::toward(b.elevation_deg, b.azimuth_deg);
            job.grid = light::make_grid(tile, rays);
            job.stream = ++stream, job.periodic = periodic;
            job.layers = layers, job.layer_m = 2.0 / static_cast<double>(layers);
            std::vector<std::uint64_t> cells(job.grid.rays(), 0);
            light::rasterize(raster.view(), light::raster_grid(job), cells.data());
            const light::Tally host = light::tally_cells(cells.data(), job, organs, s.plant_count());
            std::vector<std::uint64_t> counts(light::tally_slots(s.plant_count(), job.layers));
            gpu.count(raster.view(), light::raster_grid(job), job.layer_m,
                      static_cast<std::int32_t>(job.layers), counts.data());
            const light::Tally device =
                light::Tally::from_slots(counts.data(), job.grid.rays(), s.plant_count(), job.layers);
            INFO("seed " << seed << ", sun " << b.elevation_deg << "/" << b.azimuth_deg << ", periodic "
                         << periodic << ", " << rays << " rays, " << layers << " layers");
            CHECK(host.hits > 0);
            same(host, device);
          }
  }
}

TEST_CASE("light raster: a run on the GPU gives the host's figures") {
  const Stand s = tomato_rows(2, 5, 9);
  light::LightConfig c;
  c.suns = {{45, 200}};
  c.sky_directions = 16;
  c.tile = {-0.2, -0.5, 1.8, 1.5};
  c.plant_error = 0.01;
  c.caster = light::Caster::raster;
  PrototypeLibrary lib;
  const light::LightResult host = light::compute_light(s, lib, c);
  cuda::LightRaster gpu(0);
  c.device = &gpu;
  const light::LightResult device = light::compute_light(s, lib, c);
  CHECK(device.raster_device == gpu.name());
  CHECK(host.rays == device.rays);
  CHECK(host.direct[0].fraction.value == device.direct[0].fraction.value);
  CHECK(host.diffuse->fraction.value == device.diffuse->fraction.value);
  CHECK(host.diffuse->star.value == device.diffuse->star.value);
  for (std::size_t p = 0; p < s.plant_count(); ++p) {
    CHECK(host.direct[0].plant[p].value == device.direct[0].plant[p].value);
    CHECK(host.diffuse->plant[p].se == device.diffuse->plant[p].se);
  }
}
