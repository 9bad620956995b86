// canopy render: PNG pictures of a stand (oblique view over top view), organs coloured by kind,
// contacts in magenta. From a folder written by canopy stand: the stand as exported, with the
// contacts it still has. From a grammar: the stand grown, before resolution and after it, side by
// side.
#include "geometry/clock.hpp"
#include "geometry/export.hpp"
#include "geometry/input_file.hpp"
#include "geometry/split_list.hpp"
#include "geometry/thread_limit.hpp"
#include "lsystem/grow.hpp"
#include "tools/cli_common.hpp"
#include "tools/folder_counts.hpp"
#include "tools/detect_options.hpp"
#include "tools/resolve_options.hpp"
#include "tools/stand_options.hpp"
#ifdef CANOPY_HAVE_EMBREE
#include "tools/render/scene.hpp"
#endif

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <sys/resource.h>

#include <charconv>
#include <chrono>
#include <filesystem>
#include <fstream>

namespace canopy::cli {
namespace {

struct RenderOptions {
  std::string source, out = "stand.png", size = "1920x1080", view = "oblique";
  StandOptions stand;  // from a grammar: canopy stand's options (its files aside)
};

/// --size: two decimal whole numbers and an 'x', nothing else ("100x100abc" was 100x100).
std::pair<int, int> picture_size(const std::string& sz) {
  int w = 0, h = 0;
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
    throw std::invalid_argument(fmt::format("--size: '{}' is not WIDTHxHEIGHT between 16 and 16384", sz));
  return {w, h};
}

#ifdef CANOPY_HAVE_EMBREE
/// Organs of the organ-level rows of a stand's contacts file (contacts.csv's columns), flagged.
/// A file that is not such a table is refused by line: it was drawn as a stand without contacts.
std::vector<std::uint8_t> flags_from_csv(const std::string& path, const Stand& stand) {
  const std::size_t organs = stand.organ_count(), plants = stand.plant_count();
  std::vector<std::uint8_t> f(organs, 0);
  // A stand folder's table: one it cannot read is the folder's fault (exit 1), as read_stand's.
  std::optional<InputFile> opened;
  try {
    opened.emplace(path, "contacts table", kMaxOrgansCsvBytes);
  } catch (const FileNotFound& e) {
    throw std::runtime_error(e.what());
  }
  InputFile& in = *opened;
  std::string line;
  const std::string_view header = kContactsCsvHeader;
  if (!in.next_line(line) || line != header)
    throw std::runtime_error(
        fmt::format("{}:1: not a stand's contacts table: the header is not {}", path, header));
  const auto id = [&](std::string_view cell, std::size_t count, const char* column) {
    long long v = 0;
    const auto [end, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), v);
    if (ec != std::errc() || end != cell.data() + cell.size() || v < -1 || v >= static_cast<long long>(count))
      throw std::runtime_error(fmt::format("{}:{}: column '{}': '{}' is not -1 or an id below {}", path,
                                           in.line_number(), column, cell, count));
    return v;
  };
  while (in.next_line(line)) {
    const std::vector<std::string> cells = split_list(line);
    if (cells.size() != 5)
      throw std::runtime_error(fmt::format("{}:{}: {} cells where the table has 5 ({})", path,
                                           in.line_number(), cells.size(), header));
    if (!parse_contact_level(cells[4]))
      throw std::runtime_error(fmt::format("{}:{}: column 'level': '{}' is not plant, leaf, organ or exact",
                                           path, in.line_number(), cells[4]));
    const long long a = id(cells[0], organs, "organ_a"), b = id(cells[1], organs, "organ_b");
    id(cells[2], plants, "plant_a"), id(cells[3], plants, "plant_b");
    for (long long k : {a, b})
      if (k >= 0) f[static_cast<std::size_t>(k)] = 1;
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
  StandOptions& s = o->stand;
  add_grow_options(*app, s, "From a grammar: ");
  s.detect.add_to(*app);
  s.resolve.add_to(*app);
  return {
      app, [o, app]() -> int {
        StandOptions& s = o->stand;
        const ThreadLimit thread_limit(s.detect.threads);
        const auto [w, h] = picture_size(o->size);
        const bool folder = std::filesystem::is_directory(o->source);
        // A folder is drawn as written: options that would grow, detect or resolve are refused.
        if (folder)
          refuse_given(*app, {kGrowGroup, kLayoutGroup, kDetectGroup, kResolveGroup}, {"--threads"},
                       holds_a_stand(o->source));
        refuse_stand_file("-o", o->out);
        // Said before the work: a folder named as the picture, or a folder it cannot go in.
        refuse_file_place("-o", o->out, "PNG");
        // Nothing reads the resolution clearance of a stand that is not resolved (canopy stand
        // takes it for its compact glb's step; a picture has none).
        if (s.resolve.no_resolve && app->count("--resolve-clearance") > 0)
          throw std::invalid_argument("--resolve-clearance: with --no-resolve a picture has no use for it");
        if (s.detect.level == "plant" || s.detect.level == "leaf")
          throw std::invalid_argument(fmt::format(
              "--level {}: a picture marks the organs in contact, found at the organ or exact level",
              s.detect.level));
#ifndef CANOPY_HAVE_EMBREE
        (void)w, (void)h;
        throw std::invalid_argument(
            "canopy render: this build has no renderer (Embree was not found: apt-get install "
            "libembree-dev, then build again)");
#else
            const auto t0 = std::chrono::steady_clock::now();
            const render::View upper = o->view == "side" ? render::View::side : render::View::oblique;
            render::Image picture(w, h);
            std::size_t organs = 0;
            PrototypeLibrary lib;
            if (folder) {
              const FolderIdentity before = folder_identity(o->source, "organs.csv");
              const Stand stand = read_stand(o->source);
              print_notes(folder_count_notes(o->source, stand, before));
              organs = stand.organ_count();
              // The contacts this geometry has: after resolution, or as grown without it.
              // A link counts as there even where it leads nowhere (then its read fails, by name).
              const auto there = [](const std::string& p) {
                return std::filesystem::symlink_status(p).type() != std::filesystem::file_type::not_found;
              };
              std::string contacts = o->source + "/contacts_after.csv";
              if (!there(contacts)) contacts = o->source + "/contacts.csv";
              const std::vector<std::uint8_t> hot = there(contacts)
                                                        ? flags_from_csv(contacts, stand)
                                                        : std::vector<std::uint8_t>(organs, 0);
              const render::Scene scene(stand, lib);
              picture = panel(scene, hot, w, h, upper);
            } else {
              s.grammar = o->source;
              const DetectRequest dreq = s.detect.request();  // bad options fail before any work
              StandPlan plan = plan_stand(s);
              refuse_output_over_inputs(plan_inputs(plan, s), {}, o->out);
              print_notes(plan.grammar.notes);
              place_plan(plan, s);
              Stand stand = grow_stand(plan.request);
              if (s.target.set()) reach_target(stand, plan.layout, s.target);
              organs = stand.organ_count();
              std::string note;
              auto backend = make_backend(s.detect.backend, note);
              const Contacts before = backend->detect(stand, dreq);
              if (s.resolve.no_resolve) {
                // The stand as grown, the whole picture.
                const render::Scene scene(stand, lib);
                picture = panel(scene, flags_from(before, organs), w, h, upper);
                fmt::print("{} contacts at the {} level (not resolved)\n", before.pairs.size(),
                           kContactLevelNames[static_cast<std::size_t>(dreq.level)]);
              } else {
                {
                  const render::Scene scene(stand, lib);
                  picture.paste(panel(scene, flags_from(before, organs), w / 2, h, upper), 0, 0);
                }
                const ResolveConfig rc = s.resolve.config();
                DetectRequest at = dreq;
                at.level = rc.level;
                const Contacts start = rc.level == dreq.level ? before : backend->detect(stand, at);
                const ResolveResult r = run_resolution(stand, *backend, dreq, s.resolve, start);
                const Contacts after = backend->detect(stand, dreq);
                const render::Scene scene(stand, lib);
                picture.paste(panel(scene, flags_from(after, organs), w - w / 2, h, upper), w / 2, 0);
                fmt::print(
                    "before (left): {} contacts; after (right): {} contacts, {} organs turned (mean {:.2f} deg)\n",
                    before.pairs.size(), after.pairs.size(), r.organs_moved, r.mean_turn_deg);
              }
            }
            render::write_png(picture, o->out);
            rusage ru{};
            getrusage(RUSAGE_SELF, &ru);
            fmt::print("wrote {} ({}x{}, {} organs) in {:.2f} s, peak memory {:.2f} GB\n", o->out, w, h, organs,
                       seconds_since(t0), static_cast<double>(ru.ru_maxrss) / (1024.0 * 1024.0));
            return 0;
#endif
      }};
}

}  // namespace canopy::cli
