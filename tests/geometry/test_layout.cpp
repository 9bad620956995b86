// Layouts: counts, spacings, double rows, jitter, rotation, seeds, positions files.
#include "geometry/layout.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <unistd.h>

using namespace canopy;

TEST_CASE("rows run along +X, spaced along +Y, the first plant at the origin") {
  RowLayout l;
  l.rows = 3;
  l.per_row = 4;
  l.row_spacing = 1.5;
  l.plant_spacing = 0.4;
  const auto p = row_layout(l);
  REQUIRE(p.size() == 12);
  CHECK(p[0].x == 0);
  CHECK(p[0].y == 0);
  CHECK(p[1].x == doctest::Approx(0.4));
  CHECK(p[4].y == doctest::Approx(1.5));
  CHECK(p[11].x == doctest::Approx(1.2));
  CHECK(p[11].y == doctest::Approx(3.0));
  for (const auto& q : p) CHECK(q.rotation_deg == 0);
}

TEST_CASE("double rows: pairs GAP apart, pairs row_spacing apart") {
  RowLayout l;
  l.rows = 4;
  l.per_row = 1;
  l.row_spacing = 1.6;
  l.double_rows = 0.5;
  const auto p = row_layout(l);
  CHECK(p[0].y == 0);
  CHECK(p[1].y == doctest::Approx(0.5));
  CHECK(p[2].y == doctest::Approx(1.6));
  CHECK(p[3].y == doctest::Approx(2.1));
}

TEST_CASE("jitter stays in its disc, rotations in [0, 360), all reproducible from the seed") {
  RowLayout l;
  l.rows = 10;
  l.per_row = 50;
  l.jitter = 0.02;
  l.random_rotation = true;
  l.seed = 7;
  const auto a = row_layout(l), b = row_layout(l);
  std::set<std::uint64_t> seeds;
  double max_r = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double dx = a[i].x - (i % 50) * 0.4, dy = a[i].y - (i / 50) * 1.0;
    max_r = std::max(max_r, std::hypot(dx, dy));
    CHECK(a[i].rotation_deg >= 0);
    CHECK(a[i].rotation_deg < 360);
    CHECK(a[i].x == b[i].x);
    CHECK(a[i].seed == b[i].seed);
    CHECK(a[i].seed == plant_seed(7, i));
    seeds.insert(a[i].seed);
  }
  CHECK(max_r <= 0.02 + 1e-12);
  CHECK(max_r > 0.015);  // 500 draws fill the disc
  CHECK(seeds.size() == a.size());
  l.seed = 8;
  CHECK(row_layout(l)[0].seed != a[0].seed);
}

TEST_CASE("bad row layouts") {
  RowLayout l;
  l.plant_spacing = -1;
  CHECK_THROWS_AS(row_layout(l), std::invalid_argument);
  l.plant_spacing = 0.4;
  l.rows = 0;
  CHECK_THROWS_AS(row_layout(l), std::invalid_argument);
}

TEST_CASE("row layouts that reach past the bound on plant positions name the option") {
  const auto message = [](const RowLayout& l) {
    try {
      row_layout(l);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  RowLayout l;
  l.per_row = 2;
  l.plant_spacing = 1e300;  // wrote uninitialised memory into stand.obj
  CHECK(message(l).starts_with("--plant-spacing 1e+300 m: plants may stand at most 1e+08 m from the origin"));
  l.plant_spacing = 6e7;
  l.per_row = 3;  // 1.2e8 m for the third plant
  CHECK(message(l).starts_with("--per-row 3 x --plant-spacing 6e+07 m reaches x = 120000000 m"));
  l.per_row = 1;
  l.jitter = 2e8;
  CHECK(message(l).starts_with("--jitter 2e+08 m:"));
  l.jitter = 0;
  l.rows = 4;
  l.row_spacing = 5e7;
  l.double_rows = 4e7;  // rows at 0, 4e7, 5e7, 9e7: within
  CHECK(message(l).empty());
  l.row_spacing = 7e7;  // the second row of the second pair at 1.1e8
  CHECK(
      message(l).starts_with("--rows 4 x --row-spacing 7e+07 m with --double-rows 4e+07 m "
                             "reaches y = 110000000 m"));
  // A pair's rows on one line, or past the next pair's first row: refused, not stacked.
  for (double gap : {0.0, 7e7, 9e7}) {
    l.double_rows = gap;
    CHECK(message(l).find(
              "the two rows of a pair must be more than 0 m and less than the row spacing (7e+07 m, "
              "from pair to pair) apart") != std::string::npos);
  }
  l.rows = 2, l.double_rows = 9e7;  // one pair too: periodic light repeats it every row spacing
  CHECK(message(l).find("the two rows of a pair must be") != std::string::npos);
  // Values a grammar's stand entry gave: named by its key, the message starting at its place
  // (options never given were named before).
  l = RowLayout{};
  l.per_row = 3, l.plant_spacing = 6e7;
  l.from_grammar = {{"--per-row", "g.yaml:5:16"}, {"--plant-spacing", "g.yaml:5:42"}};
  CHECK(message(l).starts_with(
      "g.yaml:5:16: the stand entry's per_row 3 x the stand entry's plant_spacing 6e+07 m "
      "reaches x = 120000000 m"));
  l = RowLayout{};
  l.rows = 2, l.double_rows = 5;
  l.from_grammar = {{"--double-rows", "g.yaml:6:3"}};
  CHECK(message(l).starts_with("g.yaml:6:3: double rows 5 m apart (the stand entry's double_rows)"));
  // At the bound itself: accepted.
  RowLayout edge;
  edge.per_row = 2;
  edge.plant_spacing = kMaxPlantCoordinate;
  CHECK(row_layout(edge).back().x == kMaxPlantCoordinate);
}

namespace {
std::string write_temp(const std::string& text) {
  char name[] = "/tmp/canopy-positions-XXXXXX";
  const int fd = mkstemp(name);
  REQUIRE(fd >= 0);
  close(fd);
  std::ofstream(name) << text;
  return name;
}
std::string error_of(const std::string& text) {
  const std::string f = write_temp(text);
  try {
    read_positions(f);
  } catch (const std::invalid_argument& e) {
    std::remove(f.c_str());
    std::string m = e.what();
    return m.substr(f.size());
  }
  std::remove(f.c_str());
  return "";
}
std::vector<PlantPlacement> positions_of(const std::string& text) {
  const std::string f = write_temp(text);
  auto p = read_positions(f);
  std::remove(f.c_str());
  return p;
}
}  // namespace

TEST_CASE("positions files: any column order, optional grammar and steps") {
  const auto p = positions_of("seed,x,y,rotation,grammar,steps\n5,1.5,2,90,young.yaml,8\n6, 3 ,4,0,,\n");
  REQUIRE(p.size() == 2);
  CHECK(p[0].x == 1.5);
  CHECK(p[0].seed == 5);
  CHECK(p[0].grammar == "young.yaml");
  CHECK(p[0].steps == 8);
  CHECK(p[1].x == 3);
  CHECK(p[1].grammar.empty());
  CHECK_FALSE(p[1].steps.has_value());
}

TEST_CASE("positions files: cells quoted as RFC 4180 writes them") {
  // A spreadsheet quotes every cell; a grammar path with a comma is quoted as plants.csv writes it.
  const auto p = positions_of(
      "\"x\",\"y\",\"rotation\",\"seed\",\"grammar\"\n\"0.5\",\"1\",\"30\",\"7\",\"a,b.yaml\"\n"
      " 2 , \"3\" ,0,8,\"say \"\"hi\"\".yaml\"\n");
  REQUIRE(p.size() == 2);
  CHECK(p[0].x == 0.5);
  CHECK(p[0].seed == 7);
  CHECK(p[0].grammar == "a,b.yaml");
  CHECK(p[1].x == 2);
  CHECK(p[1].y == 3);
  CHECK(p[1].grammar == "say \"hi\".yaml");
  CHECK(error_of("x,y,rotation,seed\n1,\"2,0,4\n") ==
        ":2:3: a quoted cell is not closed (a quote inside one is written \"\")");
  CHECK(error_of("x,y,rotation,seed\n1,\"\",0,4\n") == ":2:3: column 'y' needs a finite number, got ''");
}

TEST_CASE("positions files from a spreadsheet: a byte-order mark and CRLF line ends") {
  const auto p = positions_of("\xEF\xBB\xBFx,y,rotation,seed\r\n0.5,1,30,7\r\n");
  REQUIRE(p.size() == 1);
  CHECK(p[0].x == 0.5);
  CHECK(p[0].rotation_deg == 30);
  CHECK(p[0].seed == 7);
  // The mark is skipped at the start of the file only: elsewhere it is a cell's text.
  CHECK(error_of("x,y,rotation,seed\n\xEF\xBB\xBF"
                 "1,2,0,4\n") ==
        ":2:1: column 'x' needs a finite number, got '\xEF\xBB\xBF"
        "1'");
}

TEST_CASE("positions files: missing columns and bad cells name the place") {
  CHECK(error_of("x,y,seed\n1,2,3\n") ==
        ":1: missing column 'rotation' (the header needs x,y,rotation,seed and may add grammar,steps)");
  CHECK(error_of("x,y,rotation,seed\n1,abc,0,1\n") == ":2:3: column 'y' needs a finite number, got 'abc'");
  CHECK(error_of("x,y,rotation,seed\n1,2,0\n") == ":2: expected 4 cells as in the header, got 3");
  CHECK(error_of("x,y,rotation,seed\n1,2,0,-4\n") == ":2:7: column 'seed' needs a whole number, got '-4'");
  CHECK(error_of("x,y,rotation,seed,steps\n1,2,0,4,2.5\n") ==
        ":2:9: column 'steps' needs a whole number from 0 to 100000, got '2.5'");
  CHECK(error_of("x;y;rotation;seed\n0,5;1;0;4\n") ==
        ":1: missing column 'x' (the header needs x,y,rotation,seed and may add grammar,steps); the cells "
        "are separated by ';' "
        "or tabs, and positions files use commas");
  CHECK(error_of("") == ": empty positions file (expected a header x,y,rotation,seed)");
  CHECK(error_of("x,y,rotation,seed\r0,0,0,1\r") ==
        ":1: the positions file's lines end with a carriage return alone (an old Mac format); save the file "
        "with "
        "\\n or \\r\\n line ends");
}

TEST_CASE("positions past the bound on plant positions name file, line and column") {
  CHECK(error_of("x,y,rotation,seed\n1e57,0,0,1\n") ==
        ":2:1: column 'x' is 1e57 m: plants may stand at most 1e+08 m from the origin");
  CHECK(error_of("x,y,rotation,seed\n0,0,0,1\n3,-1.5e8,0,2\n") ==
        ":3:3: column 'y' is -1.5e8 m: plants may stand at most 1e+08 m from the origin");
  CHECK(positions_of("x,y,rotation,seed\n-1e8,1e8,0,1\n").size() == 1);
}

TEST_CASE("seeds as written: whole numbers from 0 to 2^64 - 1 in decimal, nothing else") {
  CHECK(parse_seed("0") == std::optional<std::uint64_t>(0));
  CHECK(parse_seed("42") == std::optional<std::uint64_t>(42));
  CHECK(parse_seed("18446744073709551615") == std::optional<std::uint64_t>(18446744073709551615ULL));
  for (const char* bad : {"", "-1", "18446744073709551616", "0x10", "1.5", " 1", "1 ", "+1", "1e3", "seven"})
    CHECK_MESSAGE(!parse_seed(bad), bad);
  // A positions file takes the same seeds.
  CHECK(positions_of("x,y,rotation,seed\n0,0,0,18446744073709551615\n")[0].seed == 18446744073709551615ULL);
  CHECK(error_of("x,y,rotation,seed\n0,0,0,18446744073709551616\n") ==
        ":2:7: column 'seed' needs a whole number, got '18446744073709551616'");
}

TEST_CASE("positions files: unknown and duplicate columns are refused by name") {
  // A misspelt column was passed over: every plant grew at the default age.
  CHECK(error_of("x,y,rotation,seed,Steps\n0,0,0,1,3\n") ==
        ":1:19: unknown column 'Steps' (the header has x,y,rotation,seed and may add grammar,steps)");
  CHECK(error_of("x,y,rotation,seed,x\n0,0,0,1,3\n") ==
        ":1:19: column 'x' appears twice in the header (cells 1 and 5)");
  CHECK(error_of("x,y,rotation,seed,\n0,0,0,1,\n") ==
        ":1:19: unknown column '' (the header has x,y,rotation,seed and may add grammar,steps)");
}

TEST_CASE("positions files: steps up to 100000, numbers out of range said so") {
  CHECK(positions_of("x,y,rotation,seed,steps\n0,0,0,1,100000\n")[0].steps == 100000);
  CHECK(error_of("x,y,rotation,seed,steps\n0,0,0,1,1e9\n") ==
        ":2:9: column 'steps' needs a whole number from 0 to 100000, got '1e9'");
  CHECK(error_of("x,y,rotation,seed\n1e400,0,0,1\n") ==
        ":2:1: column 'x' needs a finite number, got '1e400', which is out of range");
}

TEST_CASE("positions files: a grammar cell names a file in the positions file's folder or below it") {
  for (const char* ok : {"tomato.yaml", "sub/young.yaml", "./a/../b.yaml", "a/b/../../c.yaml"})
    CHECK(positions_of(std::string("x,y,rotation,seed,grammar\n0,0,0,1,") + ok + "\n")[0].grammar == ok);
  CHECK(error_of("x,y,rotation,seed,grammar\n0,0,0,1,../../../../etc/shadow\n") ==
        ":2:9: column 'grammar': '../../../../etc/shadow' leaves the positions file's folder; a grammar cell "
        "names a file in the "
        "positions file's folder or below it (--any-grammar-path allows others)");
  CHECK(error_of("x,y,rotation,seed,grammar\n0,0,0,1,a/../../b.yaml\n")
            .starts_with(":2:9: column 'grammar': 'a/../../b.yaml' leaves"));
  CHECK(error_of("x,y,rotation,seed,grammar\n0,0,0,1,/etc/passwd\n")
            .starts_with(":2:9: column 'grammar': '/etc/passwd' is an absolute path"));
  // Allowed when asked for.
  const std::string f = write_temp("x,y,rotation,seed,grammar\n0,0,0,1,/etc/passwd\n1,0,0,2,../g.yaml\n");
  const auto p = read_positions(f, true);
  std::remove(f.c_str());
  REQUIRE(p.size() == 2);
  CHECK(p[0].grammar == "/etc/passwd");
  CHECK(p[1].grammar == "../g.yaml");
}

TEST_CASE("positions files that are not regular files are refused before reading") {
  CHECK_THROWS_WITH_AS(read_positions("/dev/zero"),
                       "/dev/zero: the positions file is not a regular file (a device, pipe or socket)",
                       std::invalid_argument);
  CHECK_THROWS_WITH_AS(read_positions("/tmp"), "/tmp: the positions file is a folder, not a file",
                       std::invalid_argument);
  CHECK_THROWS_AS(read_positions("/tmp/canopy-no-such-positions.csv"), FileNotFound);
}

TEST_CASE("row layouts name the length that is not finite") {
  RowLayout l;
  l.per_row = 2;
  l.jitter = INFINITY;  // was reported as plant 0's position
  CHECK_THROWS_WITH_AS(row_layout(l), "the jitter must be a finite number of metres, not negative (got inf)",
                       std::invalid_argument);
  l.jitter = 0;
  l.plant_spacing = -1;
  CHECK_THROWS_WITH_AS(row_layout(l),
                       "the plant spacing must be a finite number of metres, not negative (got -1)",
                       std::invalid_argument);
  l.plant_spacing = 0.4;
  l.double_rows = NAN;
  CHECK_THROWS_WITH_AS(row_layout(l),
                       "the double-row gap must be a finite number of metres, not negative (got nan)",
                       std::invalid_argument);
}
