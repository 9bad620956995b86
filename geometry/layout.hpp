#pragma once
/// Where plants stand (docs/design.md "Layout"): rows along +X spaced along +Y with the first plant at
/// the origin, or a positions file. Each plant gets its own seed from the stand seed.
#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace canopy {

/// A file named on the command line (or from Python) that cannot be opened.
class FileNotFound : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// The most derivation steps a plant may grow, wherever they are given (a grammar's `steps`, a
/// positions `steps` cell, --steps, Python's steps=): a hundred thousand parallel rewriting steps
/// are far past any plant's age yet still end in seconds for a grammar that does not grow.
inline constexpr int kMaxSteps = 100'000;

/// How far from the origin a plant may stand, metres, in x and in y (positions files, row layouts
/// and their spacings and jitter, the Python module). Within it a double keeps 1.5e-8 m, finer
/// than the float plant frame's 6e-8 m for organ coordinates of half a metre and more, so world
/// coordinates (stand.obj) lose nothing of the plant frame; stand.obj's numbers stay within 17
/// digits; float offsets from stand_origin (stand.ply, stand.glb) and the detection grid's cell
/// keys stay finite. Any field on Earth fits (UTM and ECEF coordinates are below 1e7 m).
inline constexpr double kMaxPlantCoordinate = 1e8;

struct PlantPlacement {
  double x = 0, y = 0;
  double rotation_deg = 0;
  std::uint64_t seed = 0;
  std::string grammar;       // empty: the stand's grammar
  std::optional<int> steps;  // empty: the grammar's (or the command line's) steps
  int source_line = 0;       // its line in the positions file (0: not read from one), for messages
};

struct RowLayout {
  int rows = 1;
  int per_row = 1;
  double row_spacing = 1.0;
  double plant_spacing = 0.4;
  /// Greenhouse double rows: rows come in pairs GAP apart; pairs are `row_spacing` apart
  /// (first row of a pair to the first row of the next).
  std::optional<double> double_rows;
  double jitter = 0;  // radius of a uniform disc around each nominal position, metres
  bool random_rotation = false;
  std::uint64_t seed = 1;
  /// Fields a grammar's stand entry gave, by the option that would otherwise give them
  /// ("--plant-spacing"): the entry's place ("FILE:LINE:COL"). A refusal that involves one names
  /// the entry's key and starts with its place instead of naming an option never given.
  std::map<std::string, std::string> from_grammar;
};

/// docs/design.md's default stand of n plants: rows of 100 (one row below 100), 1.0 m between rows,
/// 0.4 m between plants, random rotation, 2 cm jitter, stand seed 1; exactly n placements.
std::vector<PlantPlacement> default_stand_layout(int plants);

/// Plant p's seed: a hash of the stand seed and p, so plants differ and the stand is reproducible.
std::uint64_t plant_seed(std::uint64_t stand_seed, std::uint64_t plant);

/// Positions in row-major order. Throws std::invalid_argument on a negative spacing or count, and
/// naming the option for a spacing, jitter or row that reaches past kMaxPlantCoordinate.
std::vector<PlantPlacement> row_layout(const RowLayout& layout);
/// Refuses a row layout whose spacings or jitter place a plant farther than kMaxPlantCoordinate
/// from the origin, naming the options (row_layout checks it before any placement is made).
void check_reach(const RowLayout& layout);

/// A seed as written in a positions file or on the command line: a whole number from 0 to
/// 2^64 - 1 in decimal and nothing else (no sign, no spaces), or nothing.
std::optional<std::uint64_t> parse_seed(std::string_view text);

/// Reads a CSV with a header naming at least x,y,rotation,seed (and optionally grammar, steps),
/// in any column order; another column, or one named twice, is refused by name. A `grammar` cell
/// names a file relative to the positions file's folder, in it or below it, unless
/// `any_grammar_path` (--any-grammar-path) allows absolute paths and '..' above it; a `steps` cell
/// is a whole number from 0 to kMaxSteps. Errors name file, line and column; the file is read
/// with InputFile's limits (a regular file of at most kMaxPositionsBytes); an x or y past
/// kMaxPlantCoordinate is refused.
std::vector<PlantPlacement> read_positions(const std::string& path, bool any_grammar_path = false);

}  // namespace canopy
