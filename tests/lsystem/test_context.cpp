// Context-sensitive rewriting (ABOP §1.8): contexts skip branches, `ignore` names are passed over,
// checked by hand and against a naive reference on random bracketed strings.
#include "helpers.hpp"

#include <random>

using namespace canopy;
using namespace canopy::test;

namespace {

/// The textbook search, written apart from ContextIndex: walk left from i, skipping whole closed
/// branches and passing through '[' to the parent; walk right, skipping branches, stopping at ']'.
int naive_left(const ModuleString& s, const Grammar& g, int i) {
  for (int j = i - 1; j >= 0; --j) {
    const Symbol x = s.symbols[static_cast<std::size_t>(j)];
    if (x == g.symbols.close_bracket()) {
      int depth = 1;
      while (depth > 0) {
        --j;
        const Symbol y = s.symbols[static_cast<std::size_t>(j)];
        depth += y == g.symbols.close_bracket() ? 1 : y == g.symbols.open_bracket() ? -1 : 0;
      }
    } else if (x == g.symbols.open_bracket() || g.ignored[x]) {
      continue;
    } else {
      return j;
    }
  }
  return -1;
}

int naive_right(const ModuleString& s, const Grammar& g, int i) {
  const int n = static_cast<int>(s.size());
  for (int j = i + 1; j < n; ++j) {
    const Symbol x = s.symbols[static_cast<std::size_t>(j)];
    if (x == g.symbols.open_bracket()) {
      int depth = 1;
      while (depth > 0) {
        ++j;
        const Symbol y = s.symbols[static_cast<std::size_t>(j)];
        depth += y == g.symbols.open_bracket() ? 1 : y == g.symbols.close_bracket() ? -1 : 0;
      }
    } else if (x == g.symbols.close_bracket()) {
      return -1;
    } else if (g.ignored[x]) {
      continue;
    } else {
      return j;
    }
  }
  return -1;
}

}  // namespace

TEST_CASE("left context: a signal travels up an axis, skipping branches") {
  const Grammar g = grammar(R"g(
axiom: b a a [ a a ] a a
productions:
  - b < a -> b
  - b -> c
)g");
  CHECK(derived(g, 1) == "cba[aa]aa");
  CHECK(derived(g, 2) == "ccb[aa]aa");
  // The branch's first module sees the parent through '['; the module after the branch skips it.
  CHECK(derived(g, 3) == "ccc[ba]ba");
  CHECK(derived(g, 4) == "ccc[cb]cb");
}

TEST_CASE("right context: next module on the same axis, none at the end of a branch") {
  const Grammar g = grammar(R"g(
axiom: a [ a a ] a b
productions:
  - a > b -> b
)g");
  CHECK(derived(g, 1) == "a[aa]bb");
  CHECK(derived(g, 2) == "b[aa]bb");  // right context of the first a skips [aa]
  CHECK(derived(g, 3) == "b[aa]bb");  // the last a of the branch has no right context
}

TEST_CASE("ignore: named modules are invisible to context matching both ways") {
  const Grammar without = grammar(R"g(
axiom: b + F a
productions:
  - b < a -> b
)g");
  CHECK(derived(without, 1) == "b+Fa");
  const Grammar with = grammar(R"g(
axiom: b + F a
ignore: [F, "+"]
productions:
  - b < a -> b
  - a > F -> x
)g");
  CHECK(derived(with, 1) == "b+Fb");
}

TEST_CASE("contexts of several modules and parameters bound from contexts") {
  const Grammar g = grammar(R"g(
axiom: A(1) B(2) C(3) D(4)
productions:
  - "A(a) B(b) < C(c) > D(d) : a + b < c + d -> C(a + b + c + d)"
)g");
  CHECK(derived(g, 1) == "A(1)B(2)C(10)D(4)");
  CHECK(derived(g, 2) == "A(1)B(2)C(17)D(4)");  // 1 + 2 < 10 + 4 still holds
}

TEST_CASE("Hogeweg systems agree with the naive context search on every module") {
  for (const char* f : {"grammars/classic/abop_1_31a.yaml", "grammars/classic/abop_1_31b.yaml"}) {
    const Grammar g = load_grammar(source(f));
    const ModuleString s = derive(g, DeriveRequest{20, 1, kDefaultMaxModules});
    ContextIndex idx;
    idx.build(g, s);
    for (int i = 0; i < static_cast<int>(s.size()); ++i) {
      const Symbol x = s.symbols[static_cast<std::size_t>(i)];
      if (x == g.symbols.open_bracket() || x == g.symbols.close_bracket()) continue;
      REQUIRE(idx.left[static_cast<std::size_t>(i)] == naive_left(s, g, i));
      REQUIRE(idx.right[static_cast<std::size_t>(i)] == naive_right(s, g, i));
    }
  }
}

TEST_CASE("context index equals the naive search on random bracketed strings") {
  const Grammar g = grammar("axiom: a\nignore: [i]\nmodules: [b]\nproductions:\n  - a -> b\n");
  const Symbol a = static_cast<Symbol>(g.symbols.find("a")), b = static_cast<Symbol>(g.symbols.find("b")),
               ign = static_cast<Symbol>(g.symbols.find("i"));
  std::mt19937 gen(7);
  for (int trial = 0; trial < 300; ++trial) {
    ModuleString s;
    int depth = 0;
    const int n = 1 + static_cast<int>(gen() % 60);
    for (int k = 0; k < n; ++k) {
      const unsigned r = gen() % 6;
      if (r == 0) {
        s.symbols.push_back(g.symbols.open_bracket());
        ++depth;
      } else if (r == 1 && depth > 0) {
        s.symbols.push_back(g.symbols.close_bracket());
        --depth;
      } else s.symbols.push_back(r == 2 ? ign : r == 3 ? b : a);
    }
    while (depth-- > 0) s.symbols.push_back(g.symbols.close_bracket());
    ContextIndex idx;
    idx.build(g, s);
    for (int i = 0; i < static_cast<int>(s.size()); ++i) {
      const Symbol x = s.symbols[static_cast<std::size_t>(i)];
      if (x == g.symbols.open_bracket() || x == g.symbols.close_bracket()) continue;
      INFO("trial " << trial << " module " << i << " of " << format_modules(g, s));
      REQUIRE(idx.left[static_cast<std::size_t>(i)] == naive_left(s, g, i));
      REQUIRE(idx.right[static_cast<std::size_t>(i)] == naive_right(s, g, i));
    }
  }
}
