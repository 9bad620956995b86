#pragma once
/// Shared pieces of the canopy subcommands.
#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace canopy::cli {

/// A subcommand: registers its options on `app` and returns what runs it after parsing.
struct Command {
  CLI::App* app = nullptr;
  std::function<int()> run;
};

Command add_derive(CLI::App& root);
Command add_info(CLI::App& root);
Command add_stand(CLI::App& root);
Command add_detect(CLI::App& root);
Command add_sweep(CLI::App& root);

}  // namespace canopy::cli
