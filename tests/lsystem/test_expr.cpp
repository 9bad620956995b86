// The expression language: operators, precedence, functions, rand, and located errors.
#include "helpers.hpp"

#include <cmath>

using namespace canopy;
using namespace canopy::test;

namespace {

double eval(const std::string& text, std::vector<double> frame = {}, std::vector<std::string> names = {}) {
  Rng rng(1);
  const Expr e = Expr::compile(text, {"e", 1, 1}, [&](std::string_view n) -> std::optional<NameRef> {
    for (std::size_t i = 0; i < names.size(); ++i)
      if (names[i] == n) return NameRef{true, static_cast<int>(i), 0};
    if (n == "k") return NameRef{false, 0, 10};
    return std::nullopt;
  });
  return e.eval(frame.data(), rng);
}

std::string error_of(const std::string& text, std::vector<double> frame = {}) {
  return grammar_error([&] { eval(text, frame, {"x"}); });
}

}  // namespace

TEST_CASE("arithmetic, precedence and associativity") {
  CHECK(eval("1 + 2 * 3") == 7);
  CHECK(eval("(1 + 2) * 3") == 9);
  CHECK(eval("2 ^ 3 ^ 2") == 512);  // right-associative
  CHECK(eval("-2 ^ 2") == -4);      // unary minus binds below ^
  CHECK(eval("8 / 4 / 2") == 1);
  CHECK(eval("10 - 4 - 3") == 3);
  CHECK(eval("k * 2") == 20);
  CHECK(eval("x + y", {1.5, 2}, {"x", "y"}) == 3.5);
  CHECK(eval("1.5e2 + .5") == 150.5);
  CHECK(eval("pi") == doctest::Approx(3.14159265358979));
}

TEST_CASE("comparisons and logic, with short-circuit") {
  CHECK(eval("1 < 2") == 1);
  CHECK(eval("2 <= 2") == 1);
  CHECK(eval("3 > 4") == 0);
  CHECK(eval("3 >= 4") == 0);
  CHECK(eval("3 == 3") == 1);
  CHECK(eval("3 != 3") == 0);
  CHECK(eval("1 && 0") == 0);
  CHECK(eval("2 && 3") == 1);
  CHECK(eval("0 || 0") == 0);
  CHECK(eval("0 || 5") == 1);
  CHECK(eval("!0") == 1);
  CHECK(eval("!(2 > 1)") == 0);
  CHECK(eval("1 < 2 && 2 < 3 || 0") == 1);
  // The right side is not evaluated when the left decides: no division by zero here.
  CHECK(eval("x != 0 && 1 / x > 2", {0}, {"x"}) == 0);
  CHECK(eval("x == 0 || 1 / x > 2", {0}, {"x"}) == 1);
}

TEST_CASE("functions") {
  CHECK(eval("sin(0)") == 0);
  CHECK(eval("cos(0)") == 1);
  CHECK(eval("tan(pi / 4)") == doctest::Approx(1));
  CHECK(eval("sqrt(16)") == 4);
  CHECK(eval("abs(-3)") == 3);
  CHECK(eval("min(3, 1, 2)") == 1);
  CHECK(eval("max(3, 7)") == 7);
  CHECK(eval("floor(-1.5)") == -2);
  CHECK(eval("ceil(1.2)") == 2);
  for (int i = 0; i < 100; ++i) {
    const double r = eval("rand(2, 3)");
    CHECK(r >= 2);
    CHECK(r < 3);
  }
}

TEST_CASE("constant subexpressions fold at compile time, rand never does") {
  const Expr folded = Expr::compile("2 * k + 1", {}, [](std::string_view) { return NameRef{false, 0, 3}; });
  CHECK(folded.is_constant());
  const Expr drawn = Expr::compile("rand(0, 1)", {}, nullptr);
  CHECK_FALSE(drawn.is_constant());
  CHECK(drawn.uses_rand());
}

TEST_CASE("errors name the column and what was expected") {
  CHECK(error_of("1 / (x - x)", {2}) == "e:1:3: division by zero in '1 / (x - x)'");
  CHECK(error_of("y + 1") == "e:1:1: unknown name 'y': not a parameter of this production nor a constant");
  CHECK(error_of("2 * foo(1)") ==
        "e:1:5: unknown function 'foo' (known: sin cos tan sqrt abs min max floor ceil rand)");
  CHECK(error_of("sqrt(x)", {-1}) == "e:1:1: 'sqrt(x)' is not a number (NaN)");
  CHECK(error_of("10 ^ 400") == "e:1:1: '10 ^ 400' is infinite");
  CHECK(error_of("(1 + 2").find("expected ')'") != std::string::npos);
  CHECK(error_of("1 +") == "e:1:4: expression ends where a value was expected");
  CHECK(error_of("1 2") == "e:1:3: unexpected '2' in expression");
  CHECK(error_of("rand(1)") == "e:1:1: 'rand' takes 2 argument(s), got 1");
  CHECK(error_of("x = 1") == "e:1:3: '=' is not an operator; use '==' to compare");
  CHECK(error_of("") == "e:1:1: empty expression");
}
