#include "light/sampler.hpp"

#include "light/raster_stand.hpp"
#include "light/tally_grid.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>

namespace canopy::light {
OrganIndex::OrganIndex(const Stand& s) : plant(s.organ_count()), kind(s.organ_count()) {
  for (std::size_t i = 0; i < s.organ_count(); ++i)
    plant[i] = s.organs[i].plant, kind[i] = static_cast<std::uint8_t>(s.organs[i].kind);
}

Grid make_grid(const Box2d& region, double rays) {
  Grid g;
  g.region = region;
  const double n = std::max(2.0, rays);
  const double aspect = region.height() > 0 ? region.width() / region.height() : 1.0;
  const double half = std::max(1.0, std::round(std::sqrt(n * aspect) / 2));
  g.nx = 2 * static_cast<std::uint64_t>(half);
  g.ny = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::ceil(n / static_cast<double>(g.nx))));
  return g;
}

Tally trace_direction(const Scene& scene, const OrganIndex& organs, std::size_t plants,
                      const DirectionJob& job) {
  const Grid& g = job.grid;
  const RasterGrid cells = raster_grid(job);
  const Vec3d s = job.toward, d{-s.x, -s.y, -s.z};
  const double top = scene.hi().z + 1e-3;  // rays start above everything
  const double t_max = top / s.z;          // distance from the start to the ground
  const auto outcome = [&](std::uint64_t i, std::uint64_t j) {
    Vec3d ground;
    cell_point(cells, i, j, ground.x, ground.y);
    const Vec3d org = ground + s * t_max;
    const Hit hit = scene.trace(org, d, t_max);
    return outcome_of(hit.organ, org.z + d.z * hit.t, organs, job.layer_m, job.layers);
  };
  return tally_grid(g, plants, job.layers, 1, outcome);
}

}  // namespace canopy::light
