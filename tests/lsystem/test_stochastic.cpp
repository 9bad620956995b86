// Stochastic productions: reproducible from the plant's seed, frequencies as written.
#include "helpers.hpp"

#include <set>
#include <string>

using namespace canopy;
using namespace canopy::test;

namespace {
const char* kCoin = R"g(
steps: 1
axiom: A A A A A A A A A A
productions:
  - "A -> B : 0.25"
  - "A -> C : 0.75"
)g";
}

TEST_CASE("the same seed derives the same string; other seeds differ") {
  const Grammar g = grammar(kCoin);
  const std::string first = derived(g, 1, 42);
  CHECK(derived(g, 1, 42) == first);
  derived(g, 1, 7);  // another plant in between changes nothing for plant 42
  CHECK(derived(g, 1, 42) == first);
  int different = 0;
  for (std::uint64_t s = 0; s < 20; ++s) different += derived(g, 1, s) != first;
  CHECK(different >= 15);
}

TEST_CASE("frequencies over many seeds match the probabilities") {
  const Grammar g = grammar(kCoin);
  std::size_t b = 0, total = 0;
  for (std::uint64_t s = 0; s < 4000; ++s) {
    const auto counts = count_modules(g, derive(g, DeriveRequest{1, s, kDefaultMaxModules}));
    b += counts[static_cast<std::size_t>(g.symbols.find("B"))];
    total += 10;
  }
  const double p = static_cast<double>(b) / static_cast<double>(total);
  // 40,000 draws: standard error sqrt(0.25 * 0.75 / 40000) = 0.0022; allow 5 of them.
  CHECK(p == doctest::Approx(0.25).epsilon(0.011 / 0.25));
}

TEST_CASE("rand() in successors draws from the plant stream") {
  const Grammar g = grammar(R"g(
axiom: A(0)
productions:
  - "A(x) -> A(rand(0, 1)) B(rand(5, 6))"
)g");
  CHECK(derived(g, 3, 9) == derived(g, 3, 9));
  CHECK(derived(g, 3, 9) != derived(g, 3, 10));
  const ModuleString s = derive(g, DeriveRequest{1, 9, kDefaultMaxModules});
  REQUIRE(s.params.size() == 2);
  CHECK(s.params[0] >= 0);
  CHECK(s.params[0] < 1);
  CHECK(s.params[1] >= 5);
  CHECK(s.params[1] < 6);
}

TEST_CASE("a group is tried at its first member's place; conditions select before the draw") {
  const Grammar g = grammar(R"g(
axiom: A(1) A(5)
productions:
  - "A(x) : x < 3 -> S : 0.5"
  - "A(x) : x >= 3 -> L"
  - "A(x) : x < 3 -> T : 0.5"
)g");
  for (std::uint64_t s = 0; s < 20; ++s) {
    const std::string d = derived(g, 1, s);
    CHECK((d == "SL" || d == "TL"));
  }
}

TEST_CASE("probabilities within 1e-9 of 1 are accepted") {
  CHECK_NOTHROW(
      grammar("axiom: A\nproductions:\n  - 'A -> B : 0.3333333333'\n  - 'A -> C : 0.3333333333'\n  - 'A -> D "
              ": 0.3333333334'\n"));
}

TEST_CASE("a group is its modules and condition, whatever its formals are named") {
  // `A(x) -> B : 0.5` and `A(y) -> C : 0.5` match the same modules: one group (it was two, each
  // summing to 0.5). Each successor reads the parameters it names by their place.
  const Grammar g = grammar(R"g(
steps: 1
axiom: A(3) A(3) A(3) A(3) A(3) A(3) A(3) A(3)
productions:
  - "A(x) : x > 2 -> B(x) : 0.5"
  - "A(y) :y>2-> C(y * 2) : 0.5"
  - "A(z) : z > 1 -> D(z)"
)g");
  std::set<std::string> seen;
  for (std::uint64_t s = 0; s < 50; ++s) {
    const std::string d = derived(g, 1, s);
    for (std::size_t at = 0; (at = d.find_first_of("BCD", at)) != std::string::npos; ++at)
      seen.insert(d.substr(at, d.find(')', at) - at + 1));
  }
  CHECK(seen == std::set<std::string>{"B(3)", "C(6)"});  // the z > 1 production never applies
  // A formal in one production and a constant of that name in another are other conditions.
  CHECK(grammar_error([] {
          grammar("constants: {x: 1}\naxiom: A(3)\nproductions:\n  - \"A(x) : x > 2 -> B : 0.5\"\n"
                  "  - \"A(y) : x > 2 -> C : 0.5\"\n");
        }).find("sum to 0.5, not 1") != std::string::npos);
  // A name before '(' is a function even where a formal has that name: two conditions.
  CHECK(grammar_error([] {
          grammar("axiom: A(1, 0.2)\nproductions:\n  - \"A(sin, x) : sin(x) > 0.5 -> B : 0.5\"\n"
                  "  - \"A(cos, x) : cos(x) > 0.5 -> C : 0.5\"\n");
        }).find("sum to 0.5, not 1") != std::string::npos);
  // Contexts count: with and without a left context are two productions.
  CHECK(grammar_error([] {
          grammar("axiom: B A(1)\nproductions:\n  - \"B < A(x) -> C : 0.5\"\n  - \"A(y) -> D : 0.5\"\n");
        }).find("sum to 0.5, not 1") != std::string::npos);
}
