// Known answers from The Algorithmic Beauty of Plants (Prusinkiewicz & Lindenmayer 1990).
#include "helpers.hpp"

#include <map>

using namespace canopy;
using namespace canopy::test;

namespace {

/// Symbol counts after n steps of a context-free D0L-system by the growth-matrix recurrence
/// (counts_{k+1} = M counts_k), computed independently of the derivation code.
std::map<char, std::size_t> recurrence(const std::string& axiom, const std::map<char, std::string>& rules,
                                       int n) {
  std::map<char, std::size_t> c;
  for (char x : axiom) ++c[x];
  for (int k = 0; k < n; ++k) {
    std::map<char, std::size_t> next;
    for (auto [x, m] : c) {
      auto it = rules.find(x);
      if (it == rules.end()) next[x] += m;
      else
        for (char y : it->second) next[y] += m;
    }
    c = next;
  }
  return c;
}

void check_counts(const std::string& file, const std::string& axiom, const std::map<char, std::string>& rules,
                  int n) {
  const Grammar g = load_grammar(source(file));
  CHECK(g.steps == n);
  const ModuleString s = derive(g);
  const auto counts = count_modules(g, s);
  const auto want = recurrence(axiom, rules, n);
  std::size_t total = 0;
  for (auto [x, m] : want) {
    INFO(file << " symbol " << x);
    const int id = g.symbols.find(std::string(1, x));
    REQUIRE(id >= 0);
    CHECK(counts[static_cast<std::size_t>(id)] == m);
    total += m;
  }
  CHECK(s.size() == total);
}

}  // namespace

TEST_CASE("ABOP Figure 1.24: bracketed systems, symbol counts after n steps") {
  check_counts("grammars/classic/abop_1_24a.yaml", "F", {{'F', "F[+F]F[-F]F"}}, 5);
  check_counts("grammars/classic/abop_1_24b.yaml", "F", {{'F', "F[+F]F[-F][F]"}}, 5);
  check_counts("grammars/classic/abop_1_24c.yaml", "F", {{'F', "FF-[-F+F+F]+[+F-F-F]"}}, 4);
  check_counts("grammars/classic/abop_1_24d.yaml", "X", {{'X', "F[+X]F[-X]+X"}, {'F', "FF"}}, 7);
  check_counts("grammars/classic/abop_1_24e.yaml", "X", {{'X', "F[+X][-X]FX"}, {'F', "FF"}}, 7);
  check_counts("grammars/classic/abop_1_24f.yaml", "X", {{'X', "F-[[X]+X]+F[+X]-X"}, {'F', "FF"}}, 5);
}

TEST_CASE("ABOP Figure 1.24a: hand-checked values") {
  const Grammar g = load_grammar(source("grammars/classic/abop_1_24a.yaml"));
  CHECK(derived(g, 1) == "F[+F]F[-F]F");
  // 5 steps: 5^5 F, (5^5 - 1) / 2 of each bracket, (5^5 - 1) / 4 of each turn.
  CHECK(stats_json(g, derive(g)) ==
        R"({"modules": 7811, "counts": {"+": 781, "-": 781, "F": 3125, "[": 1562, "]": 1562}})");
  CHECK(derive(g, DeriveRequest{9, 1, kDefaultMaxModules}).size() == 4882811);
}

TEST_CASE("ABOP §1.2 algae: string lengths are Fibonacci numbers") {
  const Grammar g = load_grammar(source("grammars/classic/algae.yaml"));
  std::size_t a = 1, b = 2;
  CHECK(derived(g, 0) == "A");
  CHECK(derived(g, 1) == "AB");
  CHECK(derived(g, 5) == "ABAABABAABAAB");
  for (int n = 1; n <= 30; ++n) {
    CHECK(derive(g, DeriveRequest{n, 1, kDefaultMaxModules}).size() == b);
    const std::size_t c = a + b;
    a = b;
    b = c;
  }
}

TEST_CASE("ABOP Figure 1.30: the parametric derivation module by module") {
  const Grammar g = load_grammar(source("grammars/classic/abop_1_30.yaml"));
  const char* want[] = {
      "B(2)A(4,4)",
      "B(1)B(4)A(1,0)",
      "B(0)B(3)A(2,1)",
      "CB(2)A(4,3)",
      "CB(1)A(8,7)",
      "CB(0)B(8)A(1.1428571428571428,0)",  // 8/7 in shortest round-trip form
  };
  for (int n = 0; n < 6; ++n) CHECK(derived(g, n) == want[n]);
  const ModuleString s = derive(g, DeriveRequest{5, 1, kDefaultMaxModules});
  REQUIRE(s.params.size() == 4);
  CHECK(s.params[2] == 8.0 / 7.0);  // printed value reads back to the exact double
}

TEST_CASE("ABOP Figure 1.31: Hogeweg's context-sensitive systems derive and stay balanced") {
  for (const char* f : {"grammars/classic/abop_1_31a.yaml", "grammars/classic/abop_1_31b.yaml"}) {
    INFO(f);
    const Grammar g = load_grammar(source(f));
    CHECK(g.productions.context_sensitive);
    const ModuleString s = derive(g);
    long depth = 0;
    for (Symbol x : s.symbols) {
      depth += x == g.symbols.open_bracket() ? 1 : x == g.symbols.close_bracket() ? -1 : 0;
      REQUIRE(depth >= 0);
    }
    CHECK(depth == 0);
    CHECK(s.size() > 100);
  }
}
