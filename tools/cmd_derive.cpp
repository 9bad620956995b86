// canopy derive: print a grammar's derived string (before interpretation) or its module counts.
#include "lsystem/derive.hpp"
#include "lsystem/grammar.hpp"
#include "lsystem/module_format.hpp"
#include "tools/cli_common.hpp"

#include <fmt/format.h>

#include <cstdio>

namespace canopy::cli {

Command add_derive(CLI::App& root) {
  struct Options {
    std::string grammar;
    std::optional<int> steps;
    std::optional<std::uint64_t> seed;
    std::vector<std::string> set;
    bool stats = false;
    bool interpreted = false;
    std::size_t max_modules = kDefaultMaxModules;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* app = root.add_subcommand("derive", "Print the string a grammar derives, before interpretation");
  app->add_option("GRAMMAR", opt->grammar, "Grammar file (YAML)")->required();
  app->add_option("--steps", opt->steps, "Derivation steps (default: the grammar's steps)")
      ->transform(whole_in(0, kMaxSteps));
  app->add_option("--seed", opt->seed, "Seed of the plant's random stream (default: the grammar's seed)")
      ->transform(kSeed);
  app->add_option("--set", opt->set, "Override a constant: NAME=VALUE (repeatable)");
  app->add_flag("--stats", opt->stats, "Print {\"modules\": N, \"counts\": {...}} instead of the string");
  app->add_flag("--interpreted", opt->interpreted, "Apply the interpretation (homomorphism) before printing");
  app->add_option(
         "--max-modules", opt->max_modules,
         fmt::format("Stop with an error when the string would exceed this many modules (default {})",
                     kDefaultMaxModules))
      ->transform(whole_in(1, INT64_MAX));
  return {app, [opt]() {
            LoadOptions lo;
            for (const auto& s : opt->set) lo.overrides.push_back(parse_override(s));
            const Grammar g = load_grammar(opt->grammar, lo);
            print_notes(g.notes);
            DeriveRequest req;
            req.steps = opt->steps;
            req.seed = opt->seed;
            req.max_modules = opt->max_modules;
            ModuleString s = derive(g, req);
            if (opt->interpreted) s = interpret(g, s, opt->seed.value_or(g.seed), opt->max_modules);
            if (opt->stats) {
              fmt::print("{}\n", stats_json(g, s));
            } else {
              write_modules(stdout, g, s);
              std::fputc('\n', stdout);
            }
            return 0;  // output that could not be written fails the run (tools/standard_streams.hpp)
          }};
}

}  // namespace canopy::cli
