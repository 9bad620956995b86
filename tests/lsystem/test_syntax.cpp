// Module names, the printed notation and --stats.
#include "helpers.hpp"

#include <random>

using namespace canopy;
using namespace canopy::test;

TEST_CASE("declared names of several characters are matched first, longest first") {
  const Grammar g = grammar(R"g(
modules: [Ap, Apex]
axiom: Apex Ap A p FF
)g");
  const ModuleString s = derive(g, DeriveRequest{0, 1, kDefaultMaxModules});
  REQUIRE(s.size() == 6);
  CHECK(g.symbols.name(s.symbols[0]) == "Apex");
  CHECK(g.symbols.name(s.symbols[1]) == "Ap");
  CHECK(g.symbols.name(s.symbols[2]) == "A");
  CHECK(g.symbols.name(s.symbols[3]) == "p");
  CHECK(g.symbols.name(s.symbols[4]) == "F");  // FF is two F
  CHECK(g.symbols.name(s.symbols[5]) == "F");
}

TEST_CASE("the longest declared name wins where a shorter one and a dead end share its start") {
  // "Apexa" starts like "Apexes" (no name there) and holds "Apex"; "Apx" holds only "Ap".
  const Grammar g = grammar(R"g(
modules: [Ap, Apex, Apexes]
axiom: ApexaApxApexes
)g");
  const ModuleString s = derive(g, DeriveRequest{0, 1, kDefaultMaxModules});
  std::vector<std::string> names;
  for (std::size_t i = 0; i < s.size(); ++i) names.push_back(g.symbols.name(s.symbols[i]));
  CHECK(names == std::vector<std::string>{"Apex", "a", "Ap", "x", "Apexes"});
}

TEST_CASE("a production's predecessor declares its name") {
  const Grammar g = grammar(R"g(
axiom: Bud(1)
productions:
  - "Bud(n) : n < 3 -> Stem Bud(n + 1)"
  - Stem -> Stem
modules: [Stem]
)g");
  CHECK(derived(g, 2) == "StemStemBud(3)");
}

TEST_CASE("the printed string lexes back to the same modules") {
  const Grammar g = grammar(R"g(
modules: [AB, ABC, Bx]
axiom: A B C AB ABC A Bx B x D(1)
)g");
  const std::string text = derived(g, 0);
  // Spaces only where two names could read as a longer declared one (A B -> AB, B x -> Bx).
  CHECK(text == "A BCABABCA BxB xD(1)");
  const Grammar again = grammar("modules: [AB, ABC, Bx]\naxiom: '" + text + "'\n");
  CHECK(derived(again, 0) == text);
  const ModuleString a = derive(g, DeriveRequest{0, 1, kDefaultMaxModules});
  const ModuleString b = derive(again, DeriveRequest{0, 1, kDefaultMaxModules});
  REQUIRE(a.size() == b.size());
  for (std::size_t i = 0; i < a.size(); ++i)
    CHECK(g.symbols.name(a.symbols[i]) == again.symbols.name(b.symbols[i]));
  // No space where none is needed.
  CHECK(derived(grammar("axiom: F[+F]F\n"), 0) == "F[+F]F");
}

TEST_CASE("parameters print in shortest round-trip form") {
  const Grammar g = grammar("axiom: A(0.1, 1, -2.5, 1e-7, 123456789012, 1/3)\n");
  const std::string text = derived(g, 0);
  CHECK(text == "A(0.1,1,-2.5,1e-07,123456789012,0.3333333333333333)");
  const ModuleString s = derive(grammar("axiom: '" + text + "'\n"), DeriveRequest{0, 1, kDefaultMaxModules});
  CHECK(s.params[5] == 1.0 / 3.0);
  std::mt19937_64 gen(3);
  std::uniform_real_distribution<double> u(-1e6, 1e6);
  for (int i = 0; i < 200; ++i) {
    const double v = u(gen) / (1 + static_cast<double>(gen() % 1000));
    CHECK(std::stod(format_number(v)) == v);
  }
}

TEST_CASE("--stats counts every module, brackets included") {
  const Grammar g = grammar("axiom: F[+F]F[-F]F A(1)\n");
  CHECK(stats_json(g, derive(g, DeriveRequest{0, 1, kDefaultMaxModules})) ==
        R"({"modules": 12, "counts": {"+": 1, "-": 1, "A": 1, "F": 5, "[": 2, "]": 2}})");
}

TEST_CASE("interpretation is applied once after derivation and never shifts its draws") {
  const Grammar g = grammar(R"g(
axiom: A
steps: 2
productions:
  - A -> A B
interpretation:
  - B -> F(2) +
  - "A -> F(rand(1, 2))"
)g");
  const ModuleString d = derive(g);
  CHECK(format_modules(g, d) == "ABB");
  const ModuleString i = interpret(g, d, g.seed);
  CHECK(format_modules(g, i).substr(0, 2) == "F(");
  CHECK(i.size() == 5);
}

TEST_CASE("grammar keys: defaults and values") {
  const Grammar d = grammar("axiom: F\n");
  CHECK(d.angle == 90);
  CHECK(d.step == 1);
  CHECK(d.steps == 0);
  const Grammar g = grammar(R"g(
name: t
seed: 5
steps: 3
angle: 30
step: 0.07
constants: {a: 2, b: a * 3}
axiom: L(a, b)
organs:
  L: {prototype: leaflet, kind: leaflet, joint_limit: 45, lod: 3}
compound_leaf: Leaf
tropism: {direction: [0, 0, -1], strength: 0.2}
stand: {rows: 2, per_row: 5, row_spacing: 1.0, plant_spacing: 0.4, random_rotation: true, jitter: 0.02, seed: 1}
)g");
  CHECK(g.name == "t");
  CHECK(g.seed == 5);
  CHECK(g.angle == 30);
  CHECK(g.constant("b") == 6);
  CHECK(derived(g, 0) == "L(2,6)");
  const Symbol l = static_cast<Symbol>(g.symbols.find("L"));
  REQUIRE(g.organs.count(l));
  CHECK(g.organs.at(l).kind == OrganKind::leaflet);
  CHECK(g.organs.at(l).joint_limit_deg == 45);
  CHECK(g.compound_leaf == g.symbols.find("Leaf"));
  REQUIRE(g.stand);
  CHECK(g.stand->per_row == 5);
  CHECK(g.tropism->strength == 0.2);
}

TEST_CASE("--set overrides constants, and what depends on them") {
  LoadOptions o;
  o.overrides.push_back(parse_override("a=5"));
  const Grammar g = grammar("constants: {a: 2, b: a * 3}\naxiom: A(a, b)\n", o);
  CHECK(derived(g, 0) == "A(5,15)");
  CHECK_THROWS_AS(parse_override("a"), std::invalid_argument);
  CHECK_THROWS_AS(parse_override("a=x"), std::invalid_argument);
  LoadOptions bad;
  bad.overrides.push_back(parse_override("zz=1"));
  CHECK_THROWS_WITH_AS(grammar("constants: {a: 2}\naxiom: A\n", bad),
                       "--set zz: test.yaml has no constant 'zz' (its constants: a)", std::invalid_argument);
}

TEST_CASE("module cap stops exponential growth with a clear error") {
  const Grammar g = grammar("axiom: A\nproductions:\n  - A -> AA\n");
  try {
    derive(g, DeriveRequest{40, 1, 1000});
    FAIL("no error");
  } catch (const ModuleCapError& e) {
    // Named at the production that passed the cap, as every grammar error is.
    CHECK(std::string(e.what()).starts_with(
        "test.yaml:3:5: the derived string exceeds the module cap of 1000 modules at step 10, as this "
        "production applied"));
  }
  CHECK(derive(g, DeriveRequest{9, 1, 1000}).size() == 512);
  const Grammar fib = grammar("axiom: A\nproductions:\n  - A -> B\n  - B -> A B\n");
  CHECK_THROWS_WITH(derive(fib, DeriveRequest{40, 1, 100}),
                    doctest::Contains("test.yaml:4:5: the derived string exceeds the module cap of 100 "
                                        "modules at step 11"));
  // A stochastic group's member that applied, not the group's first.
  const Grammar coin = grammar("axiom: A\nproductions:\n  - \"A -> A : 0.5\"\n  - \"A -> A A A A A A A A : 0.5\"\n");
  CHECK_THROWS_WITH(derive(coin, DeriveRequest{40, 1, 1000}), doctest::Contains("test.yaml:4:6: the derived string"));
  CHECK_THROWS_WITH(derive(grammar("axiom: A A A\n"), DeriveRequest{0, 1, 2}),
                    "test.yaml:1:8: the axiom has more than the module cap of 2 modules (raise --max-modules)");
  const Grammar wide = grammar("axiom: A\ninterpretation:\n  - A -> A A A A A A\n");
  CHECK_THROWS_WITH(interpret(wide, derive(wide, DeriveRequest{0, 1, 5}), 1, 5),
                    doctest::Contains("test.yaml:3:5: the derived string exceeds the module cap of 5 "
                                        "modules in the interpretation"));
}
