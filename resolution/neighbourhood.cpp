#include "resolution/neighbourhood.hpp"

#include "geometry/obb.hpp"

#include <algorithm>
#include <cmath>

namespace canopy {

void Neighbourhood::fit_plant(const Stand& s, std::span<const Obb> boxes, std::size_t p) {
  const PlantRecord& pr = s.plants[p];
  float reach = 0;
  std::uint32_t k = pr.first_organ;
  for (std::uint32_t ri = run_first_[p]; ri < run_first_[p + 1]; ++ri) {
    OrganRun& run = runs_[ri];
    run.first = k;
    run.end = std::min(k + kRunLength, pr.first_organ + pr.organ_count);
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (std::uint32_t i = run.first; i < run.end; ++i) {
      const Obb& bi = boxes[i];
      reach = std::max(reach, std::sqrt(bi.centre.x * bi.centre.x + bi.centre.y * bi.centre.y) + bi.radius);
      const double c[3] = {bi.centre.x, bi.centre.y, bi.centre.z};
      for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], c[a]), hi[a] = std::max(hi[a], c[a]);
    }
    run.centre = Vec3f{static_cast<float>(0.5 * (lo[0] + hi[0])), static_cast<float>(0.5 * (lo[1] + hi[1])),
                       static_cast<float>(0.5 * (lo[2] + hi[2]))};
    double r = 0, slo[3] = {1e300, 1e300, 1e300}, shi[3] = {-1e300, -1e300, -1e300};
    for (std::uint32_t i = run.first; i < run.end; ++i) {
      const Obb& bi = boxes[i];
      const double dx = double(bi.centre.x) - run.centre.x, dy = double(bi.centre.y) - run.centre.y,
                   dz = double(bi.centre.z) - run.centre.z;
      r = std::max(r, std::sqrt(dx * dx + dy * dy + dz * dz) + bi.radius);
      const double c[3] = {bi.centre.x, bi.centre.y, bi.centre.z};
      for (int a = 0; a < 3; ++a)
        slo[a] = std::min(slo[a], c[a] - bi.radius), shi[a] = std::max(shi[a], c[a] + bi.radius);
    }
    run.radius = static_cast<float>(r * (1 + 1e-6) + 1e-7);  // rounded up
    const auto down = [](double v) { return static_cast<float>(v - 1e-6 * (1 + std::abs(v))); };
    const auto up = [](double v) { return static_cast<float>(v + 1e-6 * (1 + std::abs(v))); };
    run.lo = Vec3f{down(slo[0]), down(slo[1]), down(slo[2])};
    run.hi = Vec3f{up(shi[0]), up(shi[1]), up(shi[2])};
    k = run.end;
  }
  reach_[p] = reach;  // the largest horizontal distance of an organ bound from the plant's origin
}

Neighbourhood::Neighbourhood(const Stand& s, std::span<const Obb> boxes, int threads)
    : reach_(s.plant_count(), 0) {
  run_first_.assign(s.plant_count() + 1, 0);
  for (std::size_t p = 0; p < s.plant_count(); ++p)
    run_first_[p + 1] = run_first_[p] + (s.plants[p].organ_count + kRunLength - 1) / kRunLength;
  runs_.resize(run_first_.back());
  update(s, boxes, std::vector<std::uint8_t>(s.plant_count(), 1), threads);
  cell_ = std::max(0.05, 2.0 * max_reach_);
  for (std::size_t p = 0; p < s.plant_count(); ++p) {
    const Vec3d o = s.offset(p);
    cells_[key(static_cast<std::int64_t>(std::floor(o.x / cell_)),
               static_cast<std::int64_t>(std::floor(o.y / cell_)))]
        .push_back(static_cast<std::int32_t>(p));
  }
}

void Neighbourhood::update(const Stand& s, std::span<const Obb> boxes,
                           const std::vector<std::uint8_t>& plants, int threads) {
#pragma omp parallel for schedule(dynamic, 64) num_threads(threads)
  for (std::size_t p = 0; p < s.plant_count(); ++p)
    if (plants[p]) fit_plant(s, boxes, p);
  for (std::size_t p = 0; p < s.plant_count(); ++p)
    if (plants[p]) max_reach_ = std::max(max_reach_, reach_[p]);
}

std::vector<std::int32_t> Neighbourhood::plants_near(const Stand& s, double x, double y, double r) const {
  std::vector<std::int32_t> out;
  const double d = r + max_reach_;
  const auto i0 = static_cast<std::int64_t>(std::floor((x - d) / cell_)),
             i1 = static_cast<std::int64_t>(std::floor((x + d) / cell_));
  const auto j0 = static_cast<std::int64_t>(std::floor((y - d) / cell_)),
             j1 = static_cast<std::int64_t>(std::floor((y + d) / cell_));
  for (std::int64_t i = i0; i <= i1; ++i)
    for (std::int64_t j = j0; j <= j1; ++j) {
      const auto it = cells_.find(key(i, j));
      if (it == cells_.end()) continue;
      for (std::int32_t p : it->second) {
        const Vec3d o = s.offset(static_cast<std::size_t>(p));
        const double reach = r + reach_[static_cast<std::size_t>(p)];
        if ((o.x - x) * (o.x - x) + (o.y - y) * (o.y - y) <= reach * reach) out.push_back(p);
      }
    }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());  // hashed cells may repeat
  return out;
}

}  // namespace canopy
