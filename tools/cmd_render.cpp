// canopy render: PNG pictures of a stand (oblique view over top view), organs coloured by kind,
// contacts in magenta. From a folder written by canopy stand: the stand as exported, with the
// contacts it still has. From a grammar: the stand grown, before resolution and after it, side by
// side.
#include "geometry/clock.hpp"
#include "geometry/export.hpp"
#include "geometry/input_file.hpp"
#include "geometry/thread_limit.hpp"
#include "lsystem/grow.hpp"
#include "tools/cli_common.hpp"
#include "tools/detect_options.hpp"
#include "tools/resolve_options.hpp"
#ifdef CANOPY_HAVE_EMBREE
#include "tools/render/scene.hpp"
#endif

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <sys/resource.h>

#include <chrono>
#include <filesystem>
#include <fstream>

namespace canopy::cli {
namespace {

struct RenderOptions {
  std::string source, out = "stand.png", size = "1920x1080", view = "oblique";
  StandSpec rows;
  bool random_rotation = false;
  std::optional<int> steps;
  std::vector<std::string> set;
  int lod = kDefaultLod;
  DetectOptions detect;
  ResolveOptions resolve;
};

#ifdef CANOPY_HAVE_EMBREE
/// Organs of the organ-level rows of a contacts file, flagged.
std::vector<std::uint8_t> flags_from_csv(const std::string& path, std::size_t organs) {
  std::vector<std::uint8_t> f(organs, 0);
  if (!std::filesystem::exists(path)) return f;
  InputFile in(path, "contacts table", kMaxOrgansCsvBytes);
  std::string line;
  in.next_line(line);
  while (in.next_line(line)) {
    long a = -1, b = -1;
    if (std::sscanf(line.c_str(), "%ld,%ld", &a, &b) != 2) continue;
    for (long k : {a, b})
      if (k >= 0 && static_cast<std::size_t>(k) < organs) f[static_cast<std::size_t>(k)] = 1;
  }
  return f;
}

std::vector<std::uint8_t> flags_from(const Contacts& c, std::size_t organs) {
  std::vector<std::uint8_t> f(organs, 0);
  for (const Contact& x : c.pairs)
    for (std::int32_t k : {x.organ_a, x.organ_b})
      if (k >= 0) f[static_cast<std::size_t>(k)] = 1;
  return f;
}

/// The upper view (oblique or side) over the top view, in a panel of w x h.
render::Image panel(const render::Scene& scene, const std::vector<std::uint8_t>& hot, int w, int h,
                    render::View upper) {
  render::Image img(w, h);
  const int h1 = h / 2;
  img.paste(scene.render(render::fit_camera(scene.lo(), scene.hi(), upper, w, h1), hot), 0, 0);
  img.paste(scene.render(render::fit_camera(scene.lo(), scene.hi(), render::View::top, w, h - h1), hot), 0,
            h1);
  return img;
}
#endif

}  // namespace

Command add_render(CLI::App& root) {
  auto o = std::make_shared<RenderOptions>();
  CLI::App* app = root.add_subcommand(
      "render",
      "PNG pictures of a stand: oblique view over top view, contacts in magenta; from a grammar, "
      "before and after resolution side by side");
  app->add_option("SOURCE", o->source,
                  "A folder written by canopy stand, or a grammar file to grow a stand from")
      ->required();
  app->add_option("-o,--out", o->out, "PNG file to write (default stand.png)");
  app->add_option("--size", o->size, "Picture size WIDTHxHEIGHT in pixels (default 1920x1080)");
  app->add_option(
         "--view", o->view,
         "The upper view: oblique (default, from the front-left and above) or side (level, across the rows)")
      ->check(CLI::IsMember({"oblique", "side"}));
  app->add_option("--rows", o->rows.rows, "From a grammar: rows")->transform(whole_in(1, INT32_MAX));
  app->add_option("--per-row", o->rows.per_row, "From a grammar: plants per row")
      ->transform(whole_in(1, INT32_MAX));
  app->add_option("--row-spacing", o->rows.row_spacing, "From a grammar: metres between rows")
      ->check(kFinite)
      ->check(at_least(0));
  app->add_option("--plant-spacing", o->rows.plant_spacing, "From a grammar: metres between plants")
      ->check(kFinite)
      ->check(at_least(0));
  app->add_option("--jitter", o->rows.jitter, "From a grammar: jitter radius, metres")
      ->check(kFinite)
      ->check(at_least(0));
  app->add_flag("--random-rotation", o->random_rotation, "From a grammar: turn each plant at random");
  app->add_option("--seed", o->rows.seed, "From a grammar: stand seed")->transform(kSeed);
  app->add_option("--steps", o->steps, "From a grammar: derivation steps")->transform(whole_in(0, kMaxSteps));
  app->add_option("--set", o->set, "From a grammar: override a constant NAME=VALUE (repeatable)");
  app->add_option("--lod", o->lod, "From a grammar: level of detail (default 2)")
      ->transform(whole_in(1, kMaxLod));
  o->detect.add_to(*app);
  o->resolve.add_to(*app);
  return {app, [o]() -> int {
            const ThreadLimit thread_limit(o->detect.threads);
            // Two decimal whole numbers and an 'x', nothing else ("100x100abc" was 100x100).
            int w = 0, h = 0;
            const std::string& sz = o->size;
            const std::size_t x = sz.find('x');
            const auto whole = [&](std::size_t from, std::size_t to, int& v) {
              if (to <= from || to - from > 5) return false;
              for (std::size_t i = from; i < to; ++i)
                if (sz[i] < '0' || sz[i] > '9') return false;
              v = std::stoi(sz.substr(from, to - from));
              return true;
            };
            if (x == std::string::npos || !whole(0, x, w) || !whole(x + 1, sz.size(), h) || w < 16 || h < 16 ||
                w > 16384 || h > 16384)
              throw std::invalid_argument(
                  fmt::format("--size: '{}' is not WIDTHxHEIGHT between 16 and 16384", o->size));
#ifndef CANOPY_HAVE_EMBREE
            throw std::invalid_argument(
                "canopy render: this build has no renderer (Embree was not found: apt-get install "
                "libembree-dev, then build again)");
#else
            const auto t0 = std::chrono::steady_clock::now();
            const render::View upper = o->view == "side" ? render::View::side : render::View::oblique;
            render::Image picture(w, h);
            std::size_t organs = 0;
            if (std::filesystem::is_directory(o->source)) {
              const Stand stand = read_stand(o->source);
              organs = stand.organ_count();
              // The contacts this geometry has: after resolution, or as grown without it.
              std::string contacts = o->source + "/contacts_after.csv";
              if (!std::filesystem::exists(contacts)) contacts = o->source + "/contacts.csv";
              PrototypeLibrary lib;
              const render::Scene scene(stand, lib);
              picture = panel(scene, flags_from_csv(contacts, stand.organ_count()), w, h, upper);
            } else {
              GrowRequest req = grow_request(o->source, o->set, o->steps, o->lod, o->detect.threads, kDefaultMaxModules);
              if (o->random_rotation) o->rows.random_rotation = true;
              const Grammar g = load_grammar(o->source, req.load);
              req.plants = row_layout(choose_layout(o->rows, g.stand).layout);  // field by field over the grammar's entry
              Stand stand = grow_stand(req);
              organs = stand.organ_count();
              std::string note;
              auto backend = make_backend(o->detect.backend, note);
              DetectRequest dreq = o->detect.request();
              dreq.level = ContactLevel::exact;
              const Contacts before = backend->detect(stand, dreq);
              PrototypeLibrary lib;
              {
                const render::Scene scene(stand, lib);
                picture.paste(panel(scene, flags_from(before, organs), w / 2, h, upper), 0, 0);
              }
              const ResolveConfig rc = o->resolve.config();
              DetectRequest at = dreq;
              at.level = rc.level;
              const Contacts start = rc.level == ContactLevel::exact ? before : backend->detect(stand, at);
              const ResolveResult r = run_resolution(stand, *backend, dreq, o->resolve, start);
              const Contacts after = backend->detect(stand, dreq);
              const render::Scene scene(stand, lib);
              picture.paste(panel(scene, flags_from(after, organs), w - w / 2, h, upper), w / 2, 0);
              fmt::print("before (left): {} contacts; after (right): {} contacts, {} organs turned (mean {:.2f} deg)\n",
                         before.pairs.size(), after.pairs.size(), r.organs_moved, r.mean_turn_deg);
            }
            render::write_png(picture, o->out);
            rusage ru{};
            getrusage(RUSAGE_SELF, &ru);
            fmt::print("wrote {} ({}x{}, {} organs) in {:.2f} s, peak memory {:.2f} GB\n", o->out, w, h, organs,
                       seconds_since(t0),
                       static_cast<double>(ru.ru_maxrss) / (1024.0 * 1024.0));
            return 0;
#endif
          }};
}

}  // namespace canopy::cli
