// Every bad input gives one located line: file:line:column: what was expected.
#include "helpers.hpp"

using namespace canopy;
using namespace canopy::test;

namespace {
std::string error_of(const std::string& yaml) {
  return grammar_error([&] {
    const Grammar g = grammar(yaml);
    derive(g);
  });
}
}  // namespace

TEST_CASE("malformed YAML") {
  CHECK(error_of("axiom: [F\n").rfind("test.yaml:2:1: malformed YAML", 0) == 0);
  CHECK(error_of("- a\n- b\n") == "test.yaml:1:1: a grammar file is a YAML map with keys such as axiom and productions");
}

TEST_CASE("unknown and duplicate keys") {
  CHECK(error_of("axiom: F\nproduction: []\n") ==
        "test.yaml:2:1: unknown key 'production' in the grammar (expected one of: name seed steps angle step constants "
        "axiom productions interpretation ignore organs compound_leaf tropism stand modules)");
  CHECK(error_of("axiom: F\norgans:\n  L: {prototype: leaflet, kind: leaflet, colour: red}\n")
            .rfind("test.yaml:3:42: unknown key 'colour' in organ 'L'", 0) == 0);
  CHECK(error_of("axiom: F\n") == "");
  CHECK(error_of("steps: x\naxiom: F\n") == "test.yaml:1:8: steps must be a whole number, got 'x'");
  CHECK(error_of("name: a\n") == "test.yaml:1:1: the grammar has no 'axiom'");
}

TEST_CASE("unknown constant, parameter and function in expressions") {
  CHECK(error_of("axiom: A(k)\n") == "test.yaml:1:10: unknown name 'k': not a parameter of this production nor a constant");
  CHECK(error_of("axiom: A(1)\nproductions:\n  - A(x) -> A(y)\n") ==
        "test.yaml:3:15: unknown name 'y': not a parameter of this production nor a constant");
  CHECK(error_of("axiom: A(1)\nproductions:\n  - \"A(x) -> A(blend(x))\"\n") ==
        "test.yaml:3:16: unknown function 'blend' (known: sin cos tan sqrt abs min max floor ceil rand)");
  CHECK(error_of("constants: {a: b + 1}\naxiom: F\n") ==
        "test.yaml:1:16: unknown name 'b': not a parameter of this production nor a constant");
}

TEST_CASE("parameter counts") {
  CHECK(error_of("axiom: A(1) A(1, 2)\n") ==
        "test.yaml:1:13: module 'A' is used with 2 parameter(s) here but with 1 at test.yaml:1:8; a name has one "
        "parameter count");
  CHECK(error_of("axiom: A(1)\nproductions:\n  - A -> B\n").rfind("test.yaml:3:5: module 'A' is used with 0", 0) == 0);
  CHECK(error_of("axiom: L(1)\norgans:\n  L: {prototype: leaflet, kind: leaflet}\n") ==
        "test.yaml:1:8: organ 'L' is a leaflet and takes 2 to 5 parameters, but is used with 1");
  CHECK(error_of("axiom: L(1, 1, 1, 1, 1, 1)\norgans:\n  L: {prototype: leaflet, kind: leaflet}\n") ==
        "test.yaml:1:8: organ 'L' is a leaflet and takes 2 to 5 parameters, but is used with 6");
  CHECK(error_of("axiom: I(1, 1, 1)\norgans:\n  I: {prototype: cylinder, kind: internode}\n") ==
        "test.yaml:1:8: organ 'I' is a cylinder and takes 2 parameter(s), but is used with 3");
  CHECK(error_of("axiom: F(1, 2)\n") == "test.yaml:1:8: turtle symbol 'F' takes at most one parameter, got 2");
  CHECK(error_of("axiom: A(1,)\n") == "test.yaml:1:12: empty parameter in 'A'");
}

TEST_CASE("unbalanced brackets") {
  CHECK(error_of("axiom: F[+F\n") == "test.yaml:1:9: unbalanced brackets in the axiom: this '[' is never closed");
  CHECK(error_of("axiom: F\nproductions:\n  - F -> F]F\n") ==
        "test.yaml:3:11: unbalanced brackets in a successor: ']' closes no '['");
  CHECK(error_of("axiom: A(1\n") == "test.yaml:1:9: '(' after 'A' is never closed");
  CHECK(error_of("axiom: A(1))\n") == "test.yaml:1:12: ')' without a matching '('");
}

TEST_CASE("division by zero, NaN and infinity") {
  CHECK(error_of("steps: 1\naxiom: A(0)\nproductions:\n  - A(x) -> A(1/x)\n") ==
        "test.yaml:4:16: division by zero in '1/x'");
  CHECK(error_of("axiom: A(1/0)\n") == "test.yaml:1:11: division by zero in '1/0'");
  CHECK(error_of("steps: 1\naxiom: A(-1)\nproductions:\n  - A(x) -> A(sqrt(x))\n") ==
        "test.yaml:4:15: 'sqrt(x)' is not a number (NaN)");
  CHECK(error_of("steps: 3\naxiom: A(10)\nproductions:\n  - A(x) -> A(x^x)\n") ==
        "test.yaml:4:15: 'x^x' is infinite");
  CHECK(error_of("angle: .nan\naxiom: F\n") == "test.yaml:1:8: angle must be a finite number, got '.nan'");
}

TEST_CASE("stochastic groups must sum to 1") {
  CHECK(error_of("axiom: A\nproductions:\n  - \"A -> B : 0.5\"\n  - \"A -> C : 0.4\"\n") ==
        "test.yaml:3:15: the probabilities of the group '<A>:' sum to 0.9, not 1");
  CHECK(error_of("axiom: A\nproductions:\n  - \"A -> B : 0.5\"\n  - A -> C\n").find("each needs a probability") !=
        std::string::npos);
  CHECK(error_of("axiom: A\nproductions:\n  - \"A -> B : 1.5\"\n") == "test.yaml:3:15: a probability must lie in [0, 1], got 1.5");
}

TEST_CASE("invalid UTF-8 in module names (found by the fuzzer)") {
  CHECK(error_of("axiom: F\xc2\xc2\n") == "test.yaml:1:9: invalid UTF-8 in a module name");
  CHECK(error_of("axiom: F\xc3\xa9\n") == "");  // a well-formed two-byte name is fine
}

TEST_CASE("production syntax") {
  CHECK(error_of("axiom: A\nproductions:\n  - A -> B : 0.5\n") ==
        "test.yaml:3:5: this production reads as a YAML map because of ': '; quote it: - \"A -> B : ...\"");
  CHECK(error_of("axiom: A\nproductions:\n  - A B\n") == "test.yaml:3:5: expected '->' in production 'A B'");
  CHECK(error_of("axiom: A\nproductions:\n  - \" -> B\"\n") == "test.yaml:3:6: missing predecessor before '->'");
  CHECK(error_of("axiom: A(1)\nproductions:\n  - \"A(1) -> B\"\n") == "test.yaml:3:8: a formal parameter must be a name, got '1'");
  CHECK(error_of("axiom: A(1, 2)\nproductions:\n  - \"A(x, x) -> B\"\n") ==
        "test.yaml:3:11: formal parameter 'x' appears twice in this production");
  CHECK(error_of("axiom: A\nproductions:\n  - \"[ < A -> B\"\n").find("brackets are not allowed") != std::string::npos);
}

TEST_CASE("grammars that grow exponentially stop at the module cap, not out of memory") {
  const Grammar g = grammar("axiom: A\nsteps: 200\nproductions:\n  - A -> A A\n");
  CHECK_THROWS_AS(derive(g), ModuleCapError);
}
