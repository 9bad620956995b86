#include "tools/stand_options.hpp"

#include "tools/cli_common.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace canopy::cli {
namespace {

/// "From a grammar: " + "Derivation steps ..." -> "From a grammar: derivation steps ...".
std::string described(const std::string& prefix, std::string text) {
  if (!prefix.empty() && !text.empty() && text[0] >= 'A' && text[0] <= 'Z')
    text[0] = static_cast<char>(text[0] - 'A' + 'a');
  return prefix + text;
}

}  // namespace

OptionGroup::OptionGroup(CLI::App& app, std::string name)
    : app_(app), before_(app.option_defaults()->get_group()) {
  app_.option_defaults()->group(std::move(name));
}

OptionGroup::~OptionGroup() { app_.option_defaults()->group(before_); }

void add_grow_options(CLI::App& app, StandOptions& s, const std::string& prefix) {
  {
    const OptionGroup group(app, kGrowGroup);
    app.add_option("--steps", s.steps,
                   described(prefix, "Derivation steps for every plant (default: the grammar's)"))
        ->transform(whole_in(0, kMaxSteps));
    app.add_option("--set", s.set, described(prefix, "Override a constant: NAME=VALUE (repeatable)"));
    app.add_option("--lod", s.lod,
                   described(prefix, "Level of detail of prototype meshes, 1 (coarse) to 16 (default 2)"))
        ->transform(whole_in(1, kMaxLod));
    app.add_option("--max-modules", s.max_modules, described(prefix, "Module cap per plant derivation"))
        ->transform(whole_in(1, INT64_MAX));
    app.add_flag(
        "--any-grammar-path", s.any_grammar_path,
        described(prefix,
                  "Let a positions file's grammar cells name any file (an absolute path, or '..' above the "
                  "positions file's folder)"));
    add_target_options(app, s.target);
  }
  CLI::App* layout = app.add_option_group(
      kLayoutGroup,
      described(prefix,
                "Rows (each option given overrides that field of the grammar's stand entry; the others "
                "keep the entry's) or a positions file"));
  const OptionGroup group(*layout, kLayoutGroup);
  layout->add_option("--rows", s.rows.rows, "Number of rows (along +X, spaced along +Y)")
      ->transform(whole_in(1, INT32_MAX));
  layout->add_option("--per-row", s.rows.per_row, "Plants per row")->transform(whole_in(1, INT32_MAX));
  layout
      ->add_option("--row-spacing", s.rows.row_spacing,
                   "Metres between rows (default: the grammar's stand entry, else 1.0)")
      ->check(kFinite)
      ->check(at_least(0));
  layout
      ->add_option("--plant-spacing", s.rows.plant_spacing,
                   "Metres between plants in a row (default: the grammar's stand entry, else 0.4)")
      ->check(kFinite)
      ->check(at_least(0));
  layout
      ->add_option("--double-rows", s.rows.double_rows,
                   "Rows in pairs GAP metres apart; pairs --row-spacing apart")
      ->check(kFinite)
      ->check(at_least(0));
  layout->add_option("--jitter", s.rows.jitter, "Radius in metres of a uniform disc around each position")
      ->check(kFinite)
      ->check(at_least(0));
  layout->add_flag("--random-rotation", s.random_rotation, "Turn each plant by a random angle about Z");
  layout->add_flag("--no-random-rotation", s.no_random_rotation,
                   "Every plant facing the same way (overrides the grammar's stand entry)");
  layout
      ->add_option("--seed", s.rows.seed,
                   "Stand seed: plant seeds, jitter and rotations derive from it (default: the grammar's "
                   "stand entry, else 1)")
      ->transform(kSeed);
  layout->add_option("--positions", s.positions,
                     "CSV with columns x,y,rotation,seed and optional grammar,steps");
}

void add_file_options(CLI::App& app, StandOptions& s, const std::string& prefix) {
  const OptionGroup group(app, kFilesGroup);
  app.add_option("--formats", s.formats,
                 described(prefix, "Mesh formats to write, comma separated: glb,obj,ply (default glb)"));
  app.add_flag(
      "--glb-instancing", s.glb_instancing,
      described(prefix,
                "Write stand.glb with one shared mesh per prototype drawn per organ "
                "(EXT_mesh_gpu_instancing): about 20 times smaller; organ ids become a per-instance _ORGAN "
                "attribute"));
  app.add_flag(
      "--glb-compact", s.glb_compact,
      described(prefix,
                "Write stand.glb with quantized positions, normals, UVs and indices (KHR_mesh_quantization): "
                "about half the size; positions in steps below half the resolution clearance; organ id = "
                "the plant node's extras.first_organ + the _ORGAN attribute"));
}

namespace {

const CLI::Option* first_given(const CLI::App& app, std::initializer_list<std::string_view> groups,
                               std::initializer_list<std::string_view> except) {
  for (const CLI::Option* o : app.get_options()) {
    if (o->count() == 0) continue;
    const std::string& g = o->get_group();
    if (std::find(groups.begin(), groups.end(), g) == groups.end()) continue;
    if (std::find(except.begin(), except.end(), o->get_name()) != except.end()) continue;
    return o;
  }
  for (const CLI::App* sub : app.get_subcommands({}))
    if (sub->get_name().empty())  // an option group, not a subcommand
      if (const CLI::Option* o = first_given(*sub, groups, except)) return o;
  return nullptr;
}

}  // namespace

std::string holds_a_stand(const std::string& folder) {
  return fmt::format(
      "{} is a folder that holds a stand already, which this option would not change (it applies to a "
      "grammar)",
      folder);
}

void refuse_given(const CLI::App& app, std::initializer_list<std::string_view> groups,
                  std::initializer_list<std::string_view> except, const std::string& reason) {
  if (const CLI::Option* o = first_given(app, groups, except))
    throw std::invalid_argument(fmt::format("{}: {}", o->get_name(), reason));
}

}  // namespace canopy::cli
