// The turtle: frames against hand-computed matrices for each symbol, structure-tree parents and
// compound-leaf ids, organs attached to their parents' joints.
#include "geometry/prototype.hpp"
#include "helpers.hpp"
#include "lsystem/grow.hpp"
#include "lsystem/turtle.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <unistd.h>

using namespace canopy;
using namespace canopy::test;

namespace {

const char* kOrgans = R"g(
organs:
  I: {prototype: cylinder, kind: internode}
  P: {prototype: cylinder, kind: petiole}
  R: {prototype: cylinder, kind: rachis}
  L: {prototype: leaflet, kind: leaflet}
  S: {prototype: sphere, kind: fruit}
  K: {prototype: disk, kind: flower}
compound_leaf: Leaf
)g";

TurtleResult turtle(const std::string& axiom, const std::string& extra = "") {
  const Grammar g = grammar(std::string(kOrgans) + "axiom: \"" + axiom + "\"\n" + extra);
  return run_turtle(g, derive(g, DeriveRequest{0, 1, kDefaultMaxModules}), {});
}

void check_vec(Vec3f v, double x, double y, double z) {
  CHECK(v.x == doctest::Approx(x).epsilon(1e-6));
  CHECK(v.y == doctest::Approx(y).epsilon(1e-6));
  CHECK(v.z == doctest::Approx(z).epsilon(1e-6));
}

/// The heading after the given turns, read from a unit cylinder's first column.
Vec3f heading_after(const std::string& turns) { return turtle(turns + " I(1, 1)").organs.at(0).transform.c0; }
Vec3f left_after(const std::string& turns) { return turtle(turns + " I(1, 1)").organs.at(0).transform.c1; }

}  // namespace

TEST_CASE("initial frame: H = +Z, L = -Y, U = +X") {
  const Affine3f m = turtle("I(2, 0.5)").organs.at(0).transform;
  check_vec(m.c0, 0, 0, 2);     // H * length
  check_vec(m.c1, 0, -0.5, 0);  // L * radius
  check_vec(m.c2, 0.5, 0, 0);   // U * radius
  check_vec(m.t, 0, 0, 0);
}

TEST_CASE("each turtle symbol against ABOP's rotation matrices") {
  // R_U(a): H' = H cos a - L sin a. '+' = R_U(d), '-' = R_U(-d).
  check_vec(heading_after("+(90)"), 0, 1, 0);
  check_vec(heading_after("-(90)"), 0, -1, 0);
  // R_L(a): H' = H cos a + U sin a. '&' = R_L(d), '^' = R_L(-d).
  check_vec(heading_after("&(90)"), 1, 0, 0);
  check_vec(heading_after("^(90)"), -1, 0, 0);
  // R_H(a): L' = L cos a + U sin a. '\' = R_H(d), '/' = R_H(-d).
  check_vec(left_after("\\\\(90)"), 1, 0, 0);
  check_vec(left_after("/(90)"), -1, 0, 0);
  check_vec(heading_after("\\\\(90) &(90)"), 0, 1, 0);
  check_vec(heading_after("/(90) &(90)"), 0, -1, 0);
  // '|' turns around: R_U(180).
  check_vec(heading_after("|"), 0, 0, -1);
  // 30 degrees, a general angle.
  check_vec(heading_after("+(30)"), 0, std::sin(M_PI / 6), std::cos(M_PI / 6));
}

TEST_CASE("default angle and step, F and f move") {
  const TurtleResult r = turtle("F f(0.5) + I(1, 1)", "angle: 90\nstep: 2\n");
  check_vec(r.organs.at(0).transform.t, 0, 0, 2.5);
  check_vec(r.organs.at(0).transform.c0, 0, 1, 0);
  const TurtleResult a = turtle("& I(1, 1)", "angle: 45\n");
  check_vec(a.organs.at(0).transform.c0, std::sqrt(0.5), 0, std::sqrt(0.5));
}

TEST_CASE("$ rolls L into the horizontal plane, keeping H") {
  const Affine3f m = turtle("&(30) /(40) +(10) $ I(1, 1)").organs.at(0).transform;
  const Affine3f before = turtle("&(30) /(40) +(10) I(1, 1)").organs.at(0).transform;
  check_vec(m.c0, before.c0.x, before.c0.y, before.c0.z);
  CHECK(std::fabs(m.c1.z) < 1e-6);
  CHECK(length(m.c1) == doctest::Approx(1));
  CHECK(dot(m.c1, m.c0) == doctest::Approx(0).epsilon(1e-6));
}

TEST_CASE("cylinders advance; leaflets, spheres and disks do not") {
  const TurtleResult r = turtle("I(1, 0.1) L(0.2, 0.1) S(0.05) K(0.03) I(0.5, 0.1)");
  REQUIRE(r.organs.size() == 5);
  check_vec(r.organs[1].transform.t, 0, 0, 1);
  check_vec(r.organs[2].transform.t, 0, 0, 1);
  check_vec(r.organs[3].transform.t, 0, 0, 1);
  check_vec(r.organs[4].transform.t, 0, 0, 1);
  check_vec(r.organs[2].transform.c0, 0, 0, 0.05);  // sphere: radius along H, centred r ahead
}

TEST_CASE("tropism bends H towards T by e |H x T| after each cylinder (ABOP 2.2)") {
  const TurtleResult r =
      turtle("&(90) I(1, 0.1) I(1, 0.1)", "tropism: {direction: [0, 0, -1], strength: 0.2}\n");
  // After the first cylinder H = +X, |H x T| = 1: H turns 0.2 rad towards -Z.
  check_vec(r.organs[1].transform.c0, std::cos(0.2), 0, -std::sin(0.2));
}

TEST_CASE("structure tree: parents skip closed branches; compound leaves end at their branch") {
  const TurtleResult r = turtle(
      "I(1,1) [ Leaf P(1,1) [ L(1,1) ] [ L(1,1) ] R(1,1) L(1,1) ] I(1,1) [ I(1,1) ] I(1,1) [ Leaf P(1,1) ]");
  REQUIRE(r.organs.size() == 10);
  const int parent[] = {-1, 0, 1, 1, 1, 4, 0, 6, 6, 8};
  const int leaf[] = {-1, 0, 0, 0, 0, 0, -1, -1, -1, 1};
  for (std::size_t i = 0; i < 10; ++i) {
    INFO("organ " << i);
    CHECK(r.organs[i].parent == parent[i]);
    CHECK(r.organs[i].leaf == leaf[i]);
  }
  CHECK(r.leaf_count == 2);
  // A compound leaf with no organs (an unfolded bud) takes no id.
  const TurtleResult bud = turtle("I(1,1) [ Leaf ] [ Leaf P(1,1) ]");
  CHECK(bud.organs[1].leaf == 0);
  CHECK(bud.leaf_count == 1);
  // Two roots: organs with no predecessor.
  const TurtleResult roots = turtle("[ I(1,1) ] I(1,1)");
  CHECK(roots.organs[0].parent == -1);
  CHECK(roots.organs[1].parent == -1);
}

TEST_CASE("every organ of the default tomato sits on its parent's joint") {
  const Grammar g = load_grammar(source("grammars/tomato.yaml"));
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const TurtleResult r = run_turtle(
        g, interpret(g, derive(g, DeriveRequest{std::nullopt, seed, kDefaultMaxModules}), seed), {});
    REQUIRE(r.organs.size() > 200);
    int roots = 0;
    for (const OrganInstance& o : r.organs) {
      if (o.parent < 0) {
        ++roots;
        continue;
      }
      const OrganInstance& p = r.organs[static_cast<std::size_t>(o.parent)];
      const Vec3f joint =
          p.prototype == PrototypeKind::cylinder ? p.transform.t + p.transform.c0 : p.transform.t;
      CHECK(length(o.transform.t - joint) < 1e-5f);
    }
    CHECK(roots == 1);
  }
}

TEST_CASE("negative or non-finite sizes reaching the turtle are errors naming the module") {
  const Grammar g =
      grammar(std::string(kOrgans) + "axiom: I(1, 1)\nsteps: 1\nproductions:\n  - I(a, b) -> I(a - 2, b)\n");
  try {
    run_turtle(g, derive(g), {});
    FAIL("no error");
  } catch (const std::runtime_error& e) {
    CHECK(std::string(e.what()) ==
          "test.yaml: the plant, module 0 'I(-1,1)': cylinder parameter 1 must not be negative");
  }
}

TEST_CASE(
    "a non-finite position or rotation, a level of detail out of range, negative steps or threads: refused "
    "before growing") {
  // grow_stand is where rows, positions files and the Python module's arrays all arrive.
  GrowRequest req;
  req.grammar = source("grammars/tomato.yaml");
  req.steps = 3;
  req.plants.resize(3);
  req.plants[1].seed = 7;
  CHECK(grow_stand(req).plant_count() == 3);
  const double bad[] = {std::nan(""), std::numeric_limits<double>::infinity(),
                        -std::numeric_limits<double>::infinity()};
  for (const double v : bad)
    for (int field = 0; field < 3; ++field) {
      GrowRequest r = req;
      (field == 0 ? r.plants[2].x : field == 1 ? r.plants[2].y : r.plants[2].rotation_deg) = v;
      CAPTURE(field);
      CAPTURE(v);
      CHECK_THROWS_WITH_AS(grow_stand(r),
                           doctest::Contains("plant 2: its position and rotation must be finite numbers"),
                           std::invalid_argument);
    }
  // What the command line's checks refuse, refused here too (the Python module has no others).
  for (const int lod : {0, kMaxLod + 1}) {
    GrowRequest r = req;
    r.lod = lod;
    CHECK_THROWS_WITH_AS(grow_stand(r), doctest::Contains("the level of detail must lie in 1..16"),
                         std::invalid_argument);
  }
  GrowRequest r = req;
  r.threads = -1;
  CHECK_THROWS_WITH_AS(grow_stand(r), doctest::Contains("the thread count must be at least 0"),
                       std::invalid_argument);
  r.threads = 100000;  // libgomp crashed starting a team this large
  CHECK_THROWS_WITH_AS(grow_stand(r), doctest::Contains("the thread count 100000 is more than the"),
                       std::invalid_argument);
  for (const int steps : {-1, kMaxSteps + 1}) {
    r = req;
    r.steps = steps;
    const std::string all = fmt::format("the derivation steps must lie in 0..100000 (got {})", steps);
    CHECK_THROWS_WITH_AS(grow_stand(r), doctest::Contains(all.c_str()), std::invalid_argument);
    r = req;
    r.plants[1].steps = steps;
    const std::string one =
        fmt::format("plant 1: its derivation steps must lie in 0..100000 (got {})", steps);
    CHECK_THROWS_WITH_AS(grow_stand(r), doctest::Contains(one.c_str()), std::invalid_argument);
  }
}

namespace {

/// The message of what growing one plant of `yaml` (written to a file) throws, "" for none.
std::string grow_error(const std::string& yaml) {
  char name[] = "/tmp/canopy-turtle-XXXXXX";
  const int fd = mkstemp(name);
  REQUIRE(fd >= 0);
  REQUIRE(write(fd, yaml.data(), yaml.size()) == static_cast<ssize_t>(yaml.size()));
  close(fd);
  GrowRequest req;
  req.grammar = name;
  req.plants.resize(1);
  req.plants[0].seed = 1;
  std::string what;
  try {
    grow_stand(req);
  } catch (const std::exception& e) {
    what = e.what();
    if (what.starts_with(name)) what = "FILE" + what.substr(std::string(name).size());
  }
  std::remove(name);
  return what;
}

}  // namespace

TEST_CASE("organ parameter errors name the file, line and column of the expression that wrote them") {
  const std::string organs =
      "organs:\n  L: {prototype: leaflet, kind: leaflet}\n  I: {prototype: cylinder, kind: internode}\n";
  // In the axiom: the parameter's own column.
  CHECK(grow_error(organs + "axiom: L(-1,-0.5)\n") ==
        "FILE:4:10: plant 0 (seed 1), module 0 'L(-1,-0.5)': leaflet parameter 1 must not be negative");
  CHECK(grow_error(organs + "axiom: L(1, -0.5)\n") ==
        "FILE:4:13: plant 0 (seed 1), module 0 'L(1,-0.5)': leaflet parameter 2 must not be negative");
  // Computed by a production some steps on, after modules copied unchanged and a constant successor.
  CHECK(grow_error(organs +
                   "steps: 3\naxiom: F A(1)\nproductions:\n  - F -> F F\n  - A(x) -> I(1, 0.1) A(x - 1)\n"
                   "interpretation:\n  - A(x) -> L(x, 0.2)\n") ==
        "FILE:10:15: plant 0 (seed 1), module 11 'L(-2,0.2)': leaflet parameter 1 must not be negative");
  // Sizes that fit a double but not a float were written as inf and NaN.
  CHECK(grow_error(organs + "axiom: L(1e300,1e300)\n") ==
        "FILE:4:10: plant 0 (seed 1), module 0 'L(1e+300,1e+300)': leaflet parameter 1 is 1e+300 m, more "
        "than the 1000000 m an "
        "organ "
        "may measure");
  CHECK(grow_error(organs + "axiom: F(1e300) L(1, 1)\n") ==
        "FILE:4:10: plant 0 (seed 1), module 0 'F(1e+300)': the step takes the turtle farther than 1000000 m "
        "from the plant's "
        "origin");
  // A cylinder advances the turtle within the bound, as F does (its far end reached 2e6 m).
  CHECK(grow_error(organs + "axiom: I(1e6, 1) I(1e6, 1) L(1, 1)\n") ==
        "FILE:4:20: plant 0 (seed 1), module 1 'I(1e+06,1)': the cylinder takes the turtle farther than "
        "1000000 m "
        "from the plant's origin");
  CHECK(grow_error(organs + "axiom: I(1e6, 1) L(1, 1)\n") == "");  // to the bound itself
  CHECK(grow_error(organs + "axiom: L(1e6, 1e6)\n") == "");  // the bound itself is allowed
}

TEST_CASE("a leaflet's trailing parameters give its curvature; zeros give the flat leaflet") {
  const TurtleResult flat = turtle("I(1, 0.1) L(0.1, 0.05)");
  const TurtleResult zeros = turtle("I(1, 0.1) L(0.1, 0.05, 0, 0, 0)");
  REQUIRE(flat.organs.size() == 2);
  REQUIRE(zeros.organs.size() == 2);
  CHECK(zeros.organs[1].shape == 0);
  CHECK(std::memcmp(&zeros.organs[1].transform, &flat.organs[1].transform, sizeof(Affine3f)) == 0);
  CHECK(zeros.organs[1].params[0] == flat.organs[1].params[0]);
  CHECK(zeros.organs[1].params[1] == flat.organs[1].params[1]);
  // Rounded to the steps (bend 10, cup 15, fold 10 degrees); those left out are 0.
  const LeafletShape s = leaflet_shape(turtle("L(0.1, 0.05, -43, -8, 12)").organs.at(0).shape);
  CHECK(s.bend_deg == -40);
  CHECK(s.cup_deg == -15);
  CHECK(s.fold_deg == 10);
  const LeafletShape b = leaflet_shape(turtle("L(0.1, 0.05, 21)").organs.at(0).shape);
  CHECK(b.bend_deg == 20);
  CHECK(b.cup_deg == 0);
  CHECK(b.fold_deg == 0);
  // The transform is the flat leaflet's: the shape lives in the mesh.
  CHECK(std::memcmp(&turtle("L(0.1, 0.05, -43, -8, 12)").organs.at(0).transform,
                    &turtle("L(0.1, 0.05)").organs.at(0).transform, sizeof(Affine3f)) == 0);
  // An angle past its range is refused, naming the module.
  try {
    turtle("L(0.1, 0.05, -95)");
    FAIL("no error");
  } catch (const std::runtime_error& e) {
    CHECK(std::string(e.what()).find("leaflet bend must lie in [-80, 70] degrees (got -95)") !=
          std::string::npos);
    CHECK(std::string(e.what()).find("L(0.1,0.05,-95)") != std::string::npos);
  }
  CHECK_THROWS_WITH(turtle("L(0.1, 0.05, 0, 0, 45)"),
                    doctest::Contains("leaflet fold must lie in [0, 30] degrees (got 45)"));
}

TEST_CASE("plants larger than the first are summed as they grow: past the memory limit, refused") {
  // The first plant (no steps: a seedling) speaks for a stand of seedlings; the others are older.
  GrowRequest req;
  req.grammar = source("grammars/tomato.yaml");
  req.steps = 12;
  req.plants.resize(20);
  for (std::size_t p = 0; p < req.plants.size(); ++p) req.plants[p].seed = p + 1;
  req.plants[0].steps = 0;
  req.memory_limit = std::size_t{1} << 30;
  const Stand s = grow_stand(req);
  const std::size_t later = s.plants[1].organ_count;
  REQUIRE(later > 20 * (s.plants[0].organ_count + 1));
  // A limit the first plant's twenty copies fit in, and a few of the others do not.
  req.memory_limit = 5 * later * 150;
  CHECK_THROWS_WITH_AS(grow_stand(req), doctest::Contains("a stand of 20 plants needs more than the"),
                       std::runtime_error);
  req.plants[0].steps.reset();  // a first plant like the others: refused before the others grow
  CHECK_THROWS_WITH_AS(grow_stand(req), doctest::Contains("a stand of 20 plants needs about"),
                       std::runtime_error);
}
