#pragma once
/// A stand to a target (--target-lai, --target-ground-cover): the plant spacing, for the row
/// spacing and age asked, at which the stand reaches the target. Plants grow the same at any
/// spacing (their organs are in their own frames and their seeds, jitter and turns depend on
/// their place in the rows, not on distances), so the stand is grown once and its plants moved.
#include "geometry/layout.hpp"
#include "geometry/stand.hpp"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <optional>

namespace canopy::cli {

struct TargetOptions {
  std::optional<double> lai, ground_cover;
  std::optional<double> error;  // standard error of each ground cover estimate (default 0.002)
  bool set() const { return lai || ground_cover; }
};

/// Registers --target-lai, --target-ground-cover and --target-error on `app`.
void add_target_options(CLI::App& app, TargetOptions& t);

struct SpacingChoice {
  double plant_spacing = 0;
  double reached = 0, standard_error = 0;  // the target's figure at that spacing
  int evaluations = 0;
};

/// Finds the plant spacing by bisection (the figure falls as the spacing grows): LAI as leaflet
/// area over the lattice's ground (rows x per_row x plant spacing x row spacing), ground cover by
/// ray casting from the zenith, periodic over the lattice. Moves `stand`'s plants there and sets
/// `layout.plant_spacing`. Throws std::invalid_argument when the target cannot be reached
/// between 1 mm and 100 m (or with a positions file, or under a --plant-spacing also given).
SpacingChoice reach_target(Stand& stand, RowLayout& layout, const TargetOptions& t);

/// Moves the plants of `stand` (grown from `layout`'s rows) to their places for `layout`.
void place_plants(Stand& stand, const RowLayout& layout);

/// report.json's "target": what was asked and what was reached.
nlohmann::ordered_json target_json(const TargetOptions& t, const SpacingChoice& c);

}  // namespace canopy::cli
