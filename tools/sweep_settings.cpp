#include "tools/sweep_settings.hpp"
#include "tools/json_text.hpp"
#include "tools/sweep_spec.hpp"
#include "tools/sweep_table.hpp"

#include "collision/mbvt.hpp"
#include "geometry/atomic_file.hpp"
#include "lsystem/grammar.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <map>
#include <stdexcept>

namespace canopy::cli {
namespace {

/// `--sun E,A` as numbers in their shortest form ("60.0, 180" -> "60,180"), read as the light
/// reads it, so that a sweep resumed with the same sun written otherwise is the same sweep; text
/// the light refuses stays as it is (the run refuses it, with the light's message).
std::string canonical_sun(const std::string& text) {
  try {
    const auto [e, a] = number_pair("--sun", text);
    return fmt::format("{},{}", e, a);
  } catch (const std::invalid_argument&) {
    return text;
  }
}

/// The light's sun in settings read or made, canonical (older sweep.json files hold it as typed).
void canonical_light(nlohmann::ordered_json& settings) {
  if (settings.contains("light") && settings["light"].is_object() && settings["light"].contains("sun") &&
      settings["light"]["sun"].is_string())
    settings["light"]["sun"] = canonical_sun(settings["light"]["sun"].get<std::string>());
}

}  // namespace

nlohmann::ordered_json sweep_settings(const SweepOptions& o) {
  const KindMask collide = parse_collide_kinds(o.detect.collide);
  std::string kinds;
  for (std::size_t k = 0; k < collide.size(); ++k)
    if (collide[k]) kinds += (kinds.empty() ? "" : ",") + std::string(kOrganKindNames[k]);
  // --set as the grammar applies it: by name, the last value given winning (so order is no change).
  std::map<std::string, double> constants;
  for (const std::string& text : o.set) {
    const ConstantOverride c = parse_override(text);
    constants[c.name] = c.value;
  }
  nlohmann::ordered_json resolve = o.resolve.config_json();
  resolve.erase("search");  // the same turns either way, and for any number of lanes
  resolve.erase("lanes");
  nlohmann::ordered_json out = {
      {"grammar", o.grammar},
      {"grammar_digest", grammar_digest(o.grammar)},
      {"set", constants},
      {"rows", o.rows},
      {"per_row", o.per_row},
      {"jitter", o.jitter.value_or(0.02)},
      {"lod", o.lod},
      {"max_modules", o.max_modules},
      {"level", o.detect.level},
      {"clearance", o.detect.clearance},
      {"collide", kinds},
      {"resolve", resolve},
      {"light", o.no_light ? nlohmann::ordered_json(nullptr)
                           : nlohmann::ordered_json{{"sun", canonical_sun(o.sun)},
                                                    {"sky", o.sky},
                                                    {"sky_directions", o.sky_directions},
                                                    {"error", o.light_error}}}};
  // Only when off: sweeps before it turned every plant, and their sweep.json has no such key.
  if (!o.random_rotation.value_or(true)) out["random_rotation"] = false;
  return out;
}

void check_sweep_settings(const std::string& dir, const nlohmann::ordered_json& settings,
                          std::size_t finished_runs) {
  const std::string path = (std::filesystem::path(dir) / "sweep.json").string();
  // A sweep writes its settings before its first run: runs without them were made with settings
  // nothing can compare (a resumed sweep would mix two kinds of stand in one table).
  if (finished_runs > 0 && !std::filesystem::exists(path))
    throw std::invalid_argument(fmt::format(
        "sweep: {} holds {} run(s) but no sweep.json, which says with what settings they were made; give "
        "another -o, or put sweep.json back to resume it",
        dir, finished_runs));
  if (finished_runs > 0) {
    nlohmann::ordered_json before = read_sweep_settings(path);
    canonical_light(before);
    // As written (a name's bytes that are not UTF-8 became U+FFFD), so that a resumed sweep
    // compares like with like.
    const nlohmann::ordered_json now = nlohmann::ordered_json::parse(json_text(settings));
    std::string differs;
    for (const auto& [key, value] : now.items()) {
      if (key == "grammar") continue;  // the file's document is compared, not the path naming it
      // A sweep begun by a canopy of before grammar_digest kept the digest of the file's bytes.
      if (key == "grammar_digest" && before.contains(key) &&
          before.at(key) == grammar_text_digest(settings["grammar"].get<std::string>()))
        continue;
      if (!before.contains(key) || before.at(key) != value)
        differs += fmt::format("{}{} {} -> {}", differs.empty() ? "" : "; ", key,
                               before.contains(key) ? json_text(before.at(key)) : "(none)", json_text(value));
    }
    if (!differs.empty())
      throw std::invalid_argument(
          fmt::format("sweep: {} holds {} run(s) made with other settings ({}); give another -o, or the same "
                      "settings to resume it",
                      dir, finished_runs, differs));
    return;
  }
  AtomicFile out(path);
  out.write(json_text(settings, 2) + "\n");
  out.commit();
}

}  // namespace canopy::cli
