// light.json and light.csv of canopy light (docs/design.md "Command line").
#include "tools/light_run.hpp"

#ifdef CANOPY_HAVE_LIGHT
#include "tools/report.hpp"

#include <fmt/format.h>

#include <cmath>

namespace canopy::cli {
namespace {

using Json = nlohmann::ordered_json;

Json estimate(const light::Estimate& e) {
  return {{"intercepted_fraction", e.value}, {"standard_error", e.se}};
}

Json beam(const light::DirectionLight& d, const SunSpec* sun) {
  Json j;
  j["elevation"] = d.elevation_deg;
  j["azimuth"] = d.azimuth_deg;
  if (sun && sun->from_hours) j["solar_hour"] = sun->hour;
  j["intercepted_fraction"] = d.fraction.value;
  j["rays"] = d.rays;
  j["standard_error"] = d.fraction.se;
  return j;
}

/// One kind's or layer's figures: ground cover, each beam, the sky.
Json by_light(const light::LightResult& r, auto&& pick) {
  Json j;
  j["ground_cover"] = estimate(pick(r.ground));
  Json direct = Json::array();
  for (const auto& d : r.direct) direct.push_back(estimate(pick(d)));
  j["direct"] = direct;
  j["diffuse"] = r.diffuse ? estimate(pick(*r.diffuse)) : Json(nullptr);
  return j;
}

}  // namespace

Json light_json(const light::LightResult& r, const Stand& s, const LightOptions& o,
                const LightSetup& setup) {
  const std::vector<SunSpec>& suns = setup.suns;
  Json j;
  j["canopy_version"] = CANOPY_VERSION;
  j["source"] = o.source;
  Json cfg;
  cfg["sky"] = o.sky;
  cfg["sky_directions"] = o.sky_directions;
  cfg["periodic"] = r.periodic;
  cfg["error"] = o.rays_per_m2 ? Json(nullptr) : Json(o.error);
  cfg["plant_error"] = o.plant_error && !o.rays_per_m2 ? Json(*o.plant_error) : Json(nullptr);
  cfg["rays_per_m2"] = o.rays_per_m2 ? Json(*o.rays_per_m2) : Json(nullptr);
  cfg["layer_m"] = o.layer;
  cfg["ray_seed"] = o.ray_seed;
  cfg["caster"] = o.caster;
  cfg["backend"] = o.stand.detect.backend;
  if (o.latitude)
    cfg["latitude"] = *o.latitude, cfg["day"] = o.day ? Json(*o.day) : Json(nullptr), cfg["hours"] = o.hours;
  j["config"] = cfg;
  j["tile"] = setup.tile;
  j["periodic"] = r.periodic;
  j["plants"] = s.plant_count();
  j["leaf_area"] = r.leaf_area;
  j["lai"] = r.lai;
  j["ground_cover"] = r.ground.fraction.value;
  j["ground_cover_standard_error"] = r.ground.fraction.se;
  j["ground_cover_rays"] = r.ground.rays;
  j["star"] = r.diffuse ? Json(r.diffuse->star.value) : Json(nullptr);
  j["star_standard_error"] = r.diffuse ? Json(r.diffuse->star.se) : Json(nullptr);
  Json direct = Json::array();
  for (std::size_t i = 0; i < r.direct.size(); ++i)
    direct.push_back(beam(r.direct[i], i < suns.size() ? &suns[i] : nullptr));
  j["direct"] = direct;
  if (r.diffuse) {
    Json d;
    d["sky"] = light::sky_name(r.sky);
    d["directions"] = r.sky_directions.size();
    d["intercepted_fraction"] = r.diffuse->fraction.value;
    d["rays"] = r.diffuse->rays;
    d["standard_error"] = r.diffuse->fraction.se;
    Json each = Json::array();
    for (const auto& x : r.sky_directions) {
      Json e = beam(x, nullptr);
      e["weight"] = x.weight;
      e["star"] = x.star.value;
      e["star_standard_error"] = x.star.se;
      each.push_back(e);
    }
    d["per_direction"] = each;
    j["diffuse"] = d;
  } else {
    j["diffuse"] = nullptr;
  }
  // Per organ kind: the kinds the stand has.
  std::array<bool, light::kKinds> present{};
  for (const OrganRecord& x : s.organs) present[static_cast<std::size_t>(x.kind)] = true;
  Json kinds = Json::object();
  for (std::size_t k = 0; k < light::kKinds; ++k)
    if (present[k])
      kinds[std::string(kOrganKindNames[k])] =
          by_light(r, [k](const light::DirectionLight& d) { return d.kind[k]; });
  j["kinds"] = kinds;
  Json layers = Json::array();
  for (std::size_t l = 0; l < r.layer_leaf_area.size(); ++l) {
    Json x;
    x["z_from"] = r.layer_m * static_cast<double>(l);
    x["z_to"] = r.layer_m * static_cast<double>(l + 1);
    x["leaf_area"] = r.layer_leaf_area[l];
    x["lai"] = r.layer_leaf_area[l] / r.tile.area();
    const Json b = by_light(r, [l](const light::DirectionLight& d) { return d.layer[l]; });
    for (auto it = b.begin(); it != b.end(); ++it) x[it.key()] = it.value();
    layers.push_back(x);
  }
  j["profile"] = {{"layer_m", r.layer_m}, {"layers", layers}};
  j["leaf_angles"] = leaf_angles_json(r.leaf_angles);
  j["rays"] = r.rays;
  j["organs_skipped"] = r.organs_skipped;
  j["rays_rasterized"] = r.raster_rays;
  j["raster_passes"] = r.raster_passes;
  j["raster_device"] = r.raster_passes ? Json(r.raster_device) : Json(nullptr);
  j["timings_s"] = {{"scene", r.scene_s}, {"trace", r.trace_s}, {"raster", r.raster_s}};
  return j;
}

std::string light_csv(const light::LightResult& r, const Stand& s) {
  std::string out = "plant,x,y,leaf_area,ground_cover,ground_cover_se";
  for (std::size_t i = 0; i < r.direct.size(); ++i)
    out += fmt::format(",sun{0}_fraction,sun{0}_se,sun{0}_share", i + 1);
  if (r.diffuse) out += ",diffuse_fraction,diffuse_se,diffuse_share,star,star_se";
  out += "\n";
  const double n = static_cast<double>(s.plant_count());
  // A plant's share of the stand's interception: its fraction over the sum of all plants'.
  const auto share = [n](const light::DirectionLight& d, std::size_t p) {
    return d.fraction.value > 0 ? d.plant[p].value / (n * d.fraction.value) : 0.0;
  };
  for (std::size_t p = 0; p < s.plant_count(); ++p) {
    out += fmt::format("{},{},{},{},{},{}", p, s.plants[p].x, s.plants[p].y, r.plant_leaf_area[p],
                       r.ground.plant[p].value, r.ground.plant[p].se);
    for (const auto& d : r.direct)
      out += fmt::format(",{},{},{}", d.plant[p].value, d.plant[p].se, share(d, p));
    if (r.diffuse) {
      const auto& d = *r.diffuse;
      // A plant without leaflets has no STAR: empty cells.
      const bool none = std::isnan(d.plant_star[p].value);
      out += fmt::format(",{},{},{},{},{}", d.plant[p].value, d.plant[p].se, share(d, p),
                         none ? std::string() : fmt::format("{}", d.plant_star[p].value),
                         none ? std::string() : fmt::format("{}", d.plant_star[p].se));
    }
    out += "\n";
  }
  return out;
}

}  // namespace canopy::cli
#endif
