// canopy light: light interception of a stand (a folder written by canopy stand, or a grammar
// grown, detected and resolved as canopy stand does): direct beams, diffuse sky light, ground
// cover, STAR, per plant, organ kind and height layer, periodic over the tile by default.
#include "geometry/prototype.hpp"
#include "tools/cli_common.hpp"
#include "tools/light_run.hpp"
#include "tools/stand_options.hpp"

#include <fmt/format.h>

#include <filesystem>

namespace canopy::cli {

std::shared_ptr<LightOptions> register_light(CLI::App& app_ref) {
  CLI::App* app = &app_ref;
  auto o = std::make_shared<LightOptions>();
  app->add_option(
         "SOURCE", o->source,
         "A folder written by canopy stand, or a grammar to grow a stand from (with canopy stand's options)")
      ->required();
  app->add_option(
      "--sun", o->suns,
      "A direct beam: ELEVATION,AZIMUTH in degrees (azimuth clockwise from north = +Y; repeatable)");
  app->add_option("--latitude", o->latitude,
                  "Beams from the sun's position: latitude, degrees (north positive)")
      ->check(kFinite);
  app->add_option("--day", o->day, "Beams from the sun's position: day of the year, 1-366")
      ->transform(whole_in(1, 366));
  app->add_option("--hours", o->hours,
                  "Beams from the sun's position: local solar times, a list 8,10,12 or a range 8:16:2");
  app->add_option("--sky", o->sky, "Diffuse sky radiance: soc (standard overcast, default) or uniform");
  app->add_option("--sky-directions", o->sky_directions,
                  "Sky directions of equal solid angle (default 46; 0: no diffuse light, no STAR)")
      ->transform(whole_in(0, 10000));
  app->add_option("--tile", o->tile,
                  "The periodic tile XMIN,YMIN,XMAX,YMAX in metres (default: the row layout's lattice)");
  app->add_flag("--no-periodic", o->no_periodic, "An isolated stand: rays do not wrap around the tile");
  app->add_option("--error", o->error, "Standard error asked of the stand's fractions (default 0.002)")
      ->check(kFinite);
  app->add_option("--plant-error", o->plant_error,
                  "Standard error asked of each plant's fractions too (root mean square over plants)")
      ->check(kFinite);
  app->add_option("--rays-per-m2", o->rays_per_m2,
                  "Rays per m2 of ground in every direction, instead of --error")
      ->check(kFinite);
  app->add_option("--layer", o->layer, "Height of the vertical profile's layers, metres (default 0.1)")
      ->check(kFinite);
  app->add_option("--ray-seed", o->ray_seed, "Seed of the rays' positions (default 1)")->transform(kSeed);
  app->add_option("--caster", o->caster,
                  "How a pass's rays are answered: trace (Embree, ray by ray), raster (the stand's triangles "
                  "drawn over the rays' cells, on a GPU where --backend finds one, else on the host) or auto "
                  "(default: drawn on a GPU, traced on the host)")
      ->check(CLI::IsMember({"auto", "trace", "raster"}));
  // From a grammar: canopy stand's options.
  StandOptions& s = o->stand;
  {
    const OptionGroup group(*app, kFilesGroup);
    app->add_option("-o,--out", s.out, "From a grammar: the stand's folder (default out)");
  }
  add_grow_options(*app, s, "From a grammar: ");
  add_file_options(*app, s, "From a grammar: ");
  s.detect.add_to(*app);
  s.resolve.add_to(*app);
  return o;
}

void check_light_command(const CLI::App& app, LightOptions& o) {
  o.threads = o.stand.detect.threads;
  // A folder holds its stand: the options that grow, detect or resolve one would be ignored.
  if (std::filesystem::is_directory(o.source))
    refuse_given(app, {kGrowGroup, kLayoutGroup, kFilesGroup, kResolveGroup, kDetectGroup},
                 {"--threads", "--backend"}, holds_a_stand(o.source));
}

Command add_light(CLI::App& root) {
  CLI::App* app = root.add_subcommand("light",
                                      "Light interception of a stand: direct beams, diffuse sky, ground "
                                      "cover, STAR; writes light.json and light.csv");
  auto o = register_light(*app);
  return {app, [o, app]() {
            check_light_command(*app, *o);
            run_light(*o);
            return 0;
          }};
}

}  // namespace canopy::cli
