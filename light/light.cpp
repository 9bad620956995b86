#include "light/light.hpp"

#include "geometry/clock.hpp"
#include "geometry/stand_metrics.hpp"
#include "geometry/available_memory.hpp"
#include "light/leaf_layers.hpp"
#include "light/raster_stand.hpp"
#include "light/sampler.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

namespace canopy::light {
namespace {

double sq(double x) { return x * x; }

struct Run {
  const Stand& stand;
  const LightConfig& cfg;
  Scene& scene;
  const OrganIndex& organs;
  std::size_t layers;
  const std::vector<double>& plant_leaf_area;
  double leaf_area;
  PrototypeLibrary& lib;
  std::uint64_t rays = 0, raster_rays = 0;
  std::size_t raster_passes = 0, device_passes = 0;
  double raster_s = 0;
  std::unique_ptr<RasterStand> raster;  // made on the first rasterized pass
  std::unique_ptr<std::uint64_t[]> cells;
  std::size_t cells_size = 0;
  /// A first pass that met nothing is made again with this many times its rays (1: never): with a
  /// periodic tile larger than the stand's box, the rays that can meet the stand are the box's
  /// share of the tile's, and none of a few thousand may (its fractions, STAR and their errors all
  /// came out 0). Passes that met the stand are kept as they were.
  double pilot_scale = 1;

  enum class Way { trace, device, host };
  /// How a pass of `n` rays is answered: drawn on the GPU where one is given and its memory holds
  /// the cells (8 bytes a ray); else traced (automatic), or drawn on the host (raster) when its
  /// cells fit in a quarter of the memory available.
  Way way(double n) const {
    if (cfg.caster == Caster::trace) return Way::trace;
    if (cfg.device && cfg.device->fits(static_cast<std::uint64_t>(n))) return Way::device;
    if (cfg.caster == Caster::automatic) return Way::trace;
    if (n * 8 > 0.25 * static_cast<double>(memory_available()))
      throw std::invalid_argument(fmt::format(
          "--caster raster: the cells of {:.3g} rays do not fit in a quarter of the memory available; ask "
          "for a larger --error or --plant-error, fewer --rays-per-m2, or --caster trace",
          n));
    return Way::host;
  }

  /// The pass's tally from drawing the stand over its cells (drawn and counted on the device
  /// where given).
  Tally draw(const DirectionJob& job, bool on_device) {
    const auto t0 = std::chrono::steady_clock::now();
    if (!raster) raster = std::make_unique<RasterStand>(stand, lib, organs);
    const std::size_t n = job.grid.rays();
    const RasterGrid g = raster_grid(job);
    Tally t;
    if (on_device) {
      std::vector<std::uint64_t> counts(tally_slots(stand.plant_count(), layers));
      cfg.device->count(raster->view(), g, job.layer_m, static_cast<std::int32_t>(layers), counts.data());
      t = Tally::from_slots(counts.data(), n, stand.plant_count(), layers);
    } else {
      if (n > cells_size)
        cells.reset(), cells = std::make_unique_for_overwrite<std::uint64_t[]>(n), cells_size = n;
      const auto m = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static)
      for (std::int64_t c = 0; c < m; ++c) cells[static_cast<std::size_t>(c)] = 0;
      rasterize(raster->view(), g, cells.get());
      t = tally_cells(cells.get(), job, organs, stand.plant_count());
    }
    raster_rays += t.rays, ++raster_passes, device_passes += on_device, raster_s += seconds_since(t0);
    return t;
  }

  /// The ground sampled for light from `toward`: the tile when periodic, else the ground the
  /// stand's box can shade.
  Box2d region(Vec3d toward) const {
    if (cfg.periodic || !(scene.hi().x > scene.lo().x)) return cfg.tile;
    Box2d r{1e300, 1e300, -1e300, -1e300};
    for (int k = 0; k < 8; ++k) {
      const Vec3d p{(k & 1) ? scene.hi().x : scene.lo().x, (k & 2) ? scene.hi().y : scene.lo().y,
                    (k & 4) ? scene.hi().z : std::max(0.0, scene.lo().z)};
      const double x = p.x - toward.x * p.z / toward.z, y = p.y - toward.y * p.z / toward.z;
      r.x0 = std::min(r.x0, x), r.y0 = std::min(r.y0, y), r.x1 = std::max(r.x1, x), r.y1 = std::max(r.y1, y);
    }
    return r;
  }

  DirectionLight evaluate(const Tally& t, const Box2d& reg, Vec3d toward) const {
    DirectionLight d;
    d.rays = t.rays;
    const double per_ray = reg.area() / static_cast<double>(t.rays);  // ground area per ray, m2
    const double c = per_ray / cfg.tile.area();
    const double cp = c * static_cast<double>(stand.plant_count());
    const double silhouette = per_ray * toward.z;  // area across the direction per ray
    d.fraction = {static_cast<double>(t.hits) * c, std::sqrt(static_cast<double>(t.hits_diff)) * c};
    // STAR of no leaflet area is undefined (NaN: null in light.json, empty in the tables), not 0.
    const double none = std::numeric_limits<double>::quiet_NaN();
    d.star = {none, none};
    if (leaf_area > 0)
      d.star = {static_cast<double>(t.leaf) * silhouette / leaf_area,
                std::sqrt(static_cast<double>(t.leaf_diff)) * silhouette / leaf_area};
    d.plant.resize(stand.plant_count());
    d.plant_star.resize(stand.plant_count());
    for (std::size_t p = 0; p < stand.plant_count(); ++p) {
      d.plant[p] = {static_cast<double>(t.plant[p]) * cp,
                    std::sqrt(static_cast<double>(t.plant_diff[p])) * cp};
      const double la = plant_leaf_area[p];
      d.plant_star[p] = {none, none};
      if (la > 0)
        d.plant_star[p] = {static_cast<double>(t.plant_leaf[p]) * silhouette / la,
                           std::sqrt(static_cast<double>(t.plant_leaf_diff[p])) * silhouette / la};
    }
    for (std::size_t k = 0; k < kKinds; ++k)
      d.kind[k] = {static_cast<double>(t.kind[k]) * c, std::sqrt(static_cast<double>(t.kind_diff[k])) * c};
    d.layer.resize(layers);
    for (std::size_t l = 0; l < layers; ++l)
      d.layer[l] = {static_cast<double>(t.layer[l]) * c, std::sqrt(static_cast<double>(t.layer_diff[l])) * c};
    return d;
  }

  DirectionLight trace(Vec3d toward, double n, std::uint64_t stream) {
    const Box2d reg = region(toward);
    if (n > kMaxRaysPerDirection)
      throw std::invalid_argument(fmt::format(
          "the errors asked for need {:.3g} rays in one direction (the limit is {:.3g}): ask for a larger "
          "--error or --plant-error, or fewer --rays-per-m2",
          n, kMaxRaysPerDirection));
    DirectionJob job;
    job.toward = toward;
    job.grid = make_grid(reg, n);
    job.seed = cfg.seed;
    job.stream = stream;
    job.layer_m = cfg.layer_m;
    job.layers = layers;
    job.periodic = cfg.periodic;
    Tally t;
    if (const Way w = way(static_cast<double>(job.grid.rays())); w != Way::trace) {
      t = draw(job, w == Way::device);
    } else {
      scene.build();
      t = trace_direction(scene, organs, stand.plant_count(), job);
    }
    rays += t.rays;
    return evaluate(t, reg, toward);
  }

  /// A direction's first pass of `n` rays; one that met nothing, made again with pilot_scale
  /// times the rays (stream `stream` | 0xff, apart from the later passes' rounds).
  DirectionLight first_pass(Vec3d toward, double n, std::uint64_t stream) {
    DirectionLight d = trace(toward, n, stream);
    if (d.fraction.value == 0 && pilot_scale > 1) d = trace(toward, n * pilot_scale, stream | 0xff);
    return d;
  }

  static double plant_rms(const std::vector<Estimate>& v) {
    if (v.empty()) return 0;
    double s = 0;
    for (const Estimate& e : v) s += sq(e.se);
    return std::sqrt(s / static_cast<double>(v.size()));
  }

  /// How far a pass is from the asked errors: the larger of (error / asked) over the stand's
  /// and, when asked, the plants' root mean square (1 or less: met).
  double shortfall(double se, double plant_se) const {
    double r = se / cfg.error;
    if (cfg.plant_error) r = std::max(r, plant_se / *cfg.plant_error);
    return r;
  }

  /// Refuses at once errors that even the fastest decay (rays^-0.75) would reach only past the
  /// ray limit, from a pass of n rays that is r times off.
  static void check_reachable(double n, double r) {
    const double need = n * std::pow(std::max(r, 1.0), 1 / 0.75);
    if (need > kMaxRaysPerDirection)
      throw std::invalid_argument(fmt::format(
          "the errors asked for need more than {:.3g} rays in one direction (the limit is {:.3g}): ask "
          "for a larger --error or --plant-error",
          need, kMaxRaysPerDirection));
  }

  /// The exponent a of error ~ rays^-a. Independent rays fall at 0.5 and a jittered grid over
  /// smooth outlines at 0.75 (the default stand's plants measured 0.66-0.69 in bench_light), so
  /// the first step from a first pass takes 0.5, which overshoots rather than falls short; later
  /// steps take the exponent the last two passes show, within [0.5, 0.75]. A step grows the count
  /// at most kMaxStep times: the exponent steepens as the cells come to resolve the leaflets (few
  /// rays per plant behave as independent ones), so a long step from an exponent measured on
  /// coarse passes overshoots (each plant to 0.002 at 10,000 plants reached 0.0008 with 2.7 G
  /// rays when only the first step was bounded).
  static constexpr double kMaxStep = 16;
  static constexpr std::uint64_t kRounds = 16;  // passes grow at least 1.2 times: the limit stops them first
  static double decay(double n0, double r0, double n1, double r1) {
    if (!(n1 > 1.05 * n0) || !(r0 > 0) || !(r1 > 0)) return 0.5;
    return std::clamp(std::log(r0 / r1) / std::log(n1 / n0), 0.5, 0.75);
  }

  /// One direction to the asked errors: a first pass, then passes sized from the last (10% over,
  /// at least 20% more rays a pass) until the errors are met.
  DirectionLight beam(Vec3d toward, std::uint64_t id) {
    if (cfg.rays_per_m2) return trace(toward, *cfg.rays_per_m2 * region(toward).area(), id << 8);
    DirectionLight d = first_pass(toward, cfg.pilot_rays, id << 8);
    double r = shortfall(d.fraction.se, plant_rms(d.plant)), n_prev = 0, r_prev = 0;
    check_reachable(static_cast<double>(d.rays), r);
    for (std::uint64_t round = 1; round < kRounds && r > 1; ++round) {
      const double n = static_cast<double>(d.rays);
      const double a = n_prev > 0 ? decay(n_prev, r_prev, n, r) : 0.5;
      const double grow = std::max(1.2, 1.1 * std::pow(r, 1 / a));
      n_prev = n, r_prev = r;
      d = trace(toward, n * std::min(grow, kMaxStep), id << 8 | round);
      r = shortfall(d.fraction.se, plant_rms(d.plant));
    }
    return d;
  }

  /// The sky's directions combined with their weights: fractions and STAR, their errors from the
  /// directions' (independent) errors.
  DirectionLight combine(const std::vector<DirectionLight>& dirs,
                         const std::vector<SkyDirection>& sky) const {
    DirectionLight c;
    c.elevation_deg = c.azimuth_deg = 0;
    c.plant.resize(stand.plant_count()), c.plant_star.resize(stand.plant_count()), c.layer.resize(layers);
    const auto add = [](Estimate& a, const Estimate& b, double w) {
      a.value += w * b.value, a.se += sq(w * b.se);
    };
    for (std::size_t i = 0; i < dirs.size(); ++i) {
      const double w = sky[i].weight;
      const DirectionLight& d = dirs[i];
      c.rays += d.rays;
      add(c.fraction, d.fraction, w), add(c.star, d.star, w);
      for (std::size_t p = 0; p < c.plant.size(); ++p)
        add(c.plant[p], d.plant[p], w), add(c.plant_star[p], d.plant_star[p], w);
      for (std::size_t k = 0; k < kKinds; ++k) add(c.kind[k], d.kind[k], w);
      for (std::size_t l = 0; l < layers; ++l) add(c.layer[l], d.layer[l], w);
    }
    const auto root = [](Estimate& e) { e.se = std::sqrt(e.se); };
    root(c.fraction), root(c.star);
    for (auto& e : c.plant) root(e);
    for (auto& e : c.plant_star) root(e);
    for (auto& e : c.kind) root(e);
    for (auto& e : c.layer) root(e);
    return c;
  }

  /// Every sky direction: first passes, then rays shared out so the combined errors reach the
  /// asked ones with the fewest rays. With direction i's error c_i n_i^-a (c_i from its last
  /// pass) and weight w_i, minimising the rays under sum w_i^2 c_i^2 n_i^-2a = e^2 gives
  /// n_i = K (w_i c_i)^(2 / (2a + 1)), K = (sum (w_i c_i)^(2 / (2a + 1)) / e^2)^(1 / 2a) (Neyman's
  /// allocation when a = 0.5); each constraint (stand, plants) gives its n_i, the larger is taken.
  std::vector<DirectionLight> sky(const std::vector<SkyDirection>& sky, std::uint64_t first_id) {
    std::vector<DirectionLight> d(sky.size());
    std::vector<Vec3d> to(sky.size());
    for (std::size_t i = 0; i < sky.size(); ++i) to[i] = toward(sky[i].elevation_deg, sky[i].azimuth_deg);
    if (cfg.rays_per_m2) {
      for (std::size_t i = 0; i < sky.size(); ++i)
        d[i] = trace(to[i], *cfg.rays_per_m2 * region(to[i]).area(), (first_id + i) << 8);
      return d;
    }
    for (std::size_t i = 0; i < sky.size(); ++i)
      d[i] = first_pass(to[i], cfg.sky_pilot_rays, (first_id + i) << 8);
    DirectionLight c = combine(d, sky);
    double r = shortfall(c.fraction.se, plant_rms(c.plant)), n_prev = 0, r_prev = 0;
    check_reachable(static_cast<double>(cfg.sky_pilot_rays) * static_cast<double>(sky.size()), r);
    for (std::uint64_t round = 1; round < kRounds && r > 1; ++round) {
      double n_all = 0;
      for (const DirectionLight& x : d) n_all += static_cast<double>(x.rays);
      const double a = n_prev > 0 ? decay(n_prev, r_prev, n_all, r) : 0.5;
      n_prev = n_all, r_prev = r;
      const double p = 2 / (2 * a + 1);
      const auto shares = [&](auto&& error_of, double asked) {
        std::vector<double> n(sky.size(), 0);
        double sum = 0;
        for (std::size_t i = 0; i < sky.size(); ++i) {
          const double wc = sky[i].weight * error_of(d[i]) * std::pow(static_cast<double>(d[i].rays), a);
          n[i] = std::pow(wc, p), sum += n[i];
        }
        const double k = std::pow(sum / sq(asked), 1 / (2 * a));
        for (double& x : n) x *= k;
        return n;
      };
      std::vector<double> n = shares([](const DirectionLight& x) { return x.fraction.se; }, cfg.error);
      if (cfg.plant_error) {
        const std::vector<double> np =
            shares([this](const DirectionLight& x) { return plant_rms(x.plant); }, *cfg.plant_error);
        for (std::size_t i = 0; i < n.size(); ++i) n[i] = std::max(n[i], np[i]);
      }
      for (std::size_t i = 0; i < sky.size(); ++i) {
        const double have = static_cast<double>(d[i].rays);
        double want = std::max(1.1 * n[i], 1.2 * have);
        want = std::min(want, kMaxStep * have);
        if (1.1 * n[i] > have) d[i] = trace(to[i], want, (first_id + i) << 8 | round);
      }
      c = combine(d, sky);
      r = shortfall(c.fraction.se, plant_rms(c.plant));
    }
    return d;
  }
};

}  // namespace

Caster parse_caster(const std::string& name) {
  if (name == "auto") return Caster::automatic;
  if (name == "trace") return Caster::trace;
  if (name == "raster") return Caster::raster;
  throw std::invalid_argument(fmt::format("--caster: '{}' is not auto, trace or raster", name));
}

const char* caster_name(Caster c) {
  return c == Caster::trace ? "trace" : c == Caster::raster ? "raster" : "auto";
}

void check_config(const LightConfig& c) {
  const auto error_ok = [](double e) { return e >= kMinError && e <= kMaxError; };
  if (!error_ok(c.error))
    throw std::invalid_argument(fmt::format("--error: {} is not in {}..{}", c.error, kMinError, kMaxError));
  if (c.plant_error && !error_ok(*c.plant_error))
    throw std::invalid_argument(
        fmt::format("--plant-error: {} is not in {}..{}", *c.plant_error, kMinError, kMaxError));
  if (c.rays_per_m2 && !(*c.rays_per_m2 > 0 && *c.rays_per_m2 <= 1e9))
    throw std::invalid_argument(fmt::format("--rays-per-m2: {} is not in (0, 1e9]", *c.rays_per_m2));
  for (const Beam& b : c.suns) {
    if (!(b.elevation_deg > 0 && b.elevation_deg <= 90))
      throw std::invalid_argument(
          fmt::format("--sun: elevation {} is not above the horizon (0 < elevation <= 90)", b.elevation_deg));
    if (!std::isfinite(b.azimuth_deg))
      throw std::invalid_argument("--sun: the azimuth must be a finite number");
  }
  if (c.sky_directions != 0) (void)sky_directions(c.sky, c.sky_directions);
  if (!(c.tile.width() > 0 && c.tile.height() > 0 && std::isfinite(c.tile.area())))
    throw std::invalid_argument(
        fmt::format("--tile: [{}, {}] x [{}, {}] has no area", c.tile.x0, c.tile.x1, c.tile.y0, c.tile.y1));
  if (!(c.layer_m >= 1e-3 && c.layer_m <= 1e3))
    throw std::invalid_argument(fmt::format("--layer: {} m is not in 0.001..1000", c.layer_m));
  if (c.pilot_rays < 2 || c.sky_pilot_rays < 2)
    throw std::invalid_argument("first passes need at least 2 rays");
}

namespace {

/// How many copies of the tile (px x py) the path of a ray from `toward` crosses on its way down
/// through a stand `height` m tall: the copies its footprint's box meets, as Scene::trace walks
/// them (and, without periodic bounds, about how many tiles of ground the region it lights spans).
double copies_crossed(Vec3d toward, double height, double px, double py) {
  const double run = height / toward.z;  // the path's horizontal length per unit horizontal part
  return (std::abs(toward.x) * run / px + 1) * (std::abs(toward.y) * run / py + 1);
}

/// Refuses a direction so near the horizon that its rays cross more than kMaxRayCopies copies of
/// the tile: tracing walks every copy a ray's footprint meets, and drawing stretches each
/// triangle as far, so such a sun took minutes and gigabytes for light it hardly brings (a
/// horizontal surface gets sin(elevation) of it). Names the lowest elevation taken there.
void check_low_sun(double elevation_deg, double azimuth_deg, double height, double px, double py,
                   const char* what, bool sky) {
  const double n = copies_crossed(toward(elevation_deg, azimuth_deg), height, px, py);
  if (n <= kMaxRayCopies) return;
  double lo = elevation_deg, hi = 90;  // the lowest elevation within the bound, at this azimuth
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (copies_crossed(toward(mid, azimuth_deg), height, px, py) <= kMaxRayCopies ? hi : lo) = mid;
  }
  // The bound shown rounded up (3 figures), so that the value printed is taken.
  const double scale = std::pow(10.0, std::floor(std::log10(hi)) - 2);
  const double shown = std::ceil(hi / scale) * scale;
  throw std::invalid_argument(fmt::format(
      "{} at elevation {:g} degrees (azimuth {:g}): its rays cross about {:.3g} copies of the {:.3g} x "
      "{:.3g} m "
      "tile on their way down through the stand ({:.3g} m tall; at most {:g}); a sun this low lights the "
      "stand hardly at all: {}",
      what, elevation_deg, azimuth_deg, n, px, py, height, kMaxRayCopies,
      sky ? "give fewer --sky-directions (their lowest ring sinks as they grow), or a larger tile"
          : fmt::format("give one above {:.3g} degrees here, or a larger tile", shown)));
}

}  // namespace

LightResult compute_light(const Stand& stand, PrototypeLibrary& lib, const LightConfig& cfg) {
  check_config(cfg);
  LightResult r;
  r.tile = cfg.tile;
  r.periodic = cfg.periodic;
  r.sky = cfg.sky;
  r.layer_m = cfg.layer_m;
  r.plant_leaf_area = leaflet_area_per_plant(stand, lib);
  for (double a : r.plant_leaf_area) r.leaf_area += a;
  r.lai = r.leaf_area / cfg.tile.area();
  r.leaf_angles = leaf_angles(leaf_angle_sums(stand, lib));

  const auto t_scene = std::chrono::steady_clock::now();
  Scene scene(stand, lib);
  if (cfg.periodic) scene.set_period(cfg.tile.width(), cfg.tile.height());
  r.organs_skipped = scene.skipped();
  double pilot_scale = 1;
  // A stand with no organ to meet (a plant of 0 steps has none) meets nothing however many rays
  // it gets: its first passes say 0 with no error (the re-pass below cast 3.8 billion rays, 121 s,
  // for 15 empty plants under a 1 cm box).
  const bool anything = stand.organ_count() > scene.skipped();
  if (cfg.periodic && anything && scene.hi().x > scene.lo().x) {
    const double w = scene.hi().x - scene.lo().x, h = scene.hi().y - scene.lo().y;
    // A tile far larger than the stand's box (a sparse field: one plant in 10 x 10 m) leaves the
    // stand the box's share of a pass's rays: a first pass that met nothing is made again with
    // enough rays for the stand to get its configured count (Run::pilot_scale), and a tile so large
    // that such a pass would pass the ray limit is refused (a box taken at least 1 cm a side: a
    // stand in one plane still meets oblique rays).
    const double cover = std::max(w, 0.01) * std::max(h, 0.01) / cfg.tile.area();
    if (cover < 1) pilot_scale = 1 / cover;
    if (!(std::max(cfg.pilot_rays, cfg.sky_pilot_rays) * pilot_scale <= kMaxRaysPerDirection))
      throw std::invalid_argument(fmt::format(
          "--tile: a tile of {:.3g} x {:.3g} m over a stand {:.3g} x {:.3g} m wide ({:.3g} times its area): "
          "a "
          "pass would need more than {:.3g} rays to meet the stand; give a tile nearer the stand's size (its "
          "lattice: plant spacing x row spacing per plant)",
          cfg.tile.width(), cfg.tile.height(), w, h, 1 / cover, kMaxRaysPerDirection));
    const double copies = std::ceil(w / cfg.tile.width()) * std::ceil(h / cfg.tile.height());
    if (!(copies <= kMaxTileCopies))
      throw std::invalid_argument(
          fmt::format("--tile: a tile of {:.3g} x {:.3g} m under a stand {:.3g} x {:.3g} m wide puts {:.3g} "
                      "copies of the stand "
                      "over each point (at most {}): give a tile nearer the stand's size (its lattice: plant "
                      "spacing x row "
                      "spacing per plant)",
                      cfg.tile.width(), cfg.tile.height(), w, h, copies, kMaxTileCopies));
  }
  if (scene.hi().z > scene.lo().z) {
    const double height = scene.hi().z - std::min(0.0, scene.lo().z);
    for (const Beam& b : cfg.suns)
      check_low_sun(b.elevation_deg, b.azimuth_deg, height, cfg.tile.width(), cfg.tile.height(),
                    "a sun (--sun, --hours)", false);
    if (cfg.sky_directions > 0)
      for (const SkyDirection& d : sky_directions(cfg.sky, cfg.sky_directions))
        check_low_sun(d.elevation_deg, d.azimuth_deg, height, cfg.tile.width(), cfg.tile.height(),
                      "--sky-directions: a sky direction", true);
  }
  const OrganIndex organs(stand);
  r.scene_s = seconds_since(t_scene);
  const double layers_d = std::ceil(std::max(scene.hi().z, 0.0) / cfg.layer_m);
  if (layers_d > static_cast<double>(kMaxLayers))
    throw std::invalid_argument(
        fmt::format("--layer: {} m cuts the stand ({:.3g} m tall) into more than {} layers", cfg.layer_m,
                    scene.hi().z, kMaxLayers));
  const std::size_t layers = std::max<std::size_t>(1, static_cast<std::size_t>(layers_d));
  r.layer_leaf_area = layer_leaf_area(stand, lib, cfg.layer_m, layers);

  const auto t_trace = std::chrono::steady_clock::now();
  Run run{stand, cfg, scene, organs, layers, r.plant_leaf_area, r.leaf_area, lib, 0, 0, 0,
          0,     0,   {},    {},     0,      pilot_scale};
  r.ground = run.beam({0, 0, 1}, 0);
  for (std::size_t i = 0; i < cfg.suns.size(); ++i) {
    const Beam& b = cfg.suns[i];
    DirectionLight d = run.beam(toward(b.elevation_deg, b.azimuth_deg), 1 + i);
    d.elevation_deg = b.elevation_deg, d.azimuth_deg = b.azimuth_deg;
    r.direct.push_back(std::move(d));
  }
  if (cfg.sky_directions > 0) {
    const std::vector<SkyDirection> sky = sky_directions(cfg.sky, cfg.sky_directions);
    r.sky_directions = run.sky(sky, 1 + cfg.suns.size());
    for (std::size_t i = 0; i < sky.size(); ++i) {
      r.sky_directions[i].elevation_deg = sky[i].elevation_deg;
      r.sky_directions[i].azimuth_deg = sky[i].azimuth_deg;
      r.sky_directions[i].weight = sky[i].weight;
    }
    r.diffuse = run.combine(r.sky_directions, sky);
  }
  r.trace_s = seconds_since(t_trace) - scene.build_s();
  r.scene_s += scene.build_s();
  r.rays = run.rays;
  r.raster_rays = run.raster_rays, r.raster_passes = run.raster_passes, r.raster_s = run.raster_s;
  if (run.raster_passes) r.raster_device = run.device_passes ? cfg.device->name() : "host";
  return r;
}

}  // namespace canopy::light
