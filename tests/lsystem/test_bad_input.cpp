// Every bad input gives one located line: file:line:column: what was expected.
#include "helpers.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>

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
  CHECK(error_of("- a\n- b\n") ==
        "test.yaml:1:1: a grammar file is a YAML map with keys such as axiom and productions");
}

TEST_CASE("unknown and duplicate keys") {
  CHECK(error_of("axiom: F\nproduction: []\n") ==
        "test.yaml:2:1: unknown key 'production' in the grammar (expected one of: name seed steps angle step "
        "constants "
        "axiom productions interpretation ignore organs compound_leaf tropism stand modules)");
  CHECK(error_of("axiom: F\norgans:\n  L: {prototype: leaflet, kind: leaflet, colour: red}\n")
            .rfind("test.yaml:3:42: unknown key 'colour' in organ 'L'", 0) == 0);
  CHECK(error_of("axiom: F\n") == "");
  CHECK(error_of("steps: x\naxiom: F\n") == "test.yaml:1:8: steps must be a whole number, got 'x'");
  CHECK(error_of("name: a\n") == "test.yaml:1:1: the grammar has no 'axiom'");
}

TEST_CASE("unknown constant, parameter and function in expressions") {
  CHECK(error_of("axiom: A(k)\n") ==
        "test.yaml:1:10: unknown name 'k': not a parameter of this production nor a constant");
  CHECK(error_of("axiom: A(1)\nproductions:\n  - A(x) -> A(y)\n") ==
        "test.yaml:3:15: unknown name 'y': not a parameter of this production nor a constant");
  CHECK(error_of("axiom: A(1)\nproductions:\n  - \"A(x) -> A(blend(x))\"\n") ==
        "test.yaml:3:16: unknown function 'blend' (known: sin cos tan sqrt abs min max floor ceil rand)");
  CHECK(error_of("constants: {a: b + 1}\naxiom: F\n") ==
        "test.yaml:1:16: unknown name 'b': not a parameter of this production nor a constant");
}

TEST_CASE("parameter counts") {
  CHECK(error_of("axiom: A(1) A(1, 2)\n") ==
        "test.yaml:1:13: module 'A' is used with 2 parameter(s) here but with 1 at test.yaml:1:8; a name has "
        "one "
        "parameter count");
  CHECK(error_of("axiom: A(1)\nproductions:\n  - A -> B\n")
            .rfind("test.yaml:3:5: module 'A' is used with 0", 0) == 0);
  CHECK(error_of("axiom: L(1)\norgans:\n  L: {prototype: leaflet, kind: leaflet}\n") ==
        "test.yaml:1:8: organ 'L' is a leaflet and takes 2 to 5 parameters, but is used with 1");
  CHECK(error_of("axiom: L(1, 1, 1, 1, 1, 1)\norgans:\n  L: {prototype: leaflet, kind: leaflet}\n") ==
        "test.yaml:1:8: organ 'L' is a leaflet and takes 2 to 5 parameters, but is used with 6");
  CHECK(error_of("axiom: I(1, 1, 1)\norgans:\n  I: {prototype: cylinder, kind: internode}\n") ==
        "test.yaml:1:8: organ 'I' is a cylinder and takes 2 parameter(s), but is used with 3");
  CHECK(error_of("axiom: F(1, 2)\n") ==
        "test.yaml:1:8: turtle symbol 'F' takes at most one parameter, got 2");
  CHECK(error_of("axiom: A(1,)\n") == "test.yaml:1:12: empty parameter in 'A'");
}

TEST_CASE("unbalanced brackets") {
  CHECK(error_of("axiom: F[+F\n") ==
        "test.yaml:1:9: unbalanced brackets in the axiom: this '[' is never closed");
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

TEST_CASE("a NaN or infinity inside an expression is not hidden by what comes after it") {
  // A comparison, min or max, && || !, pow with exponent 0 gave a finite answer: the condition
  // sqrt(-1) > 1 was false, min(sqrt(-1), 1) was 1 (found by a probe).
  const auto cond = [](const std::string& c) {
    return error_of("steps: 1\naxiom: A(-1)\nproductions:\n  - \"A(x) : " + c + " -> B\"\n");
  };
  CHECK(cond("sqrt(x) > 1") == "test.yaml:4:13: 'sqrt(x) > 1' is not a number (NaN)");
  CHECK(cond("sqrt(x) != sqrt(x)") == "test.yaml:4:13: 'sqrt(x) != sqrt(x)' is not a number (NaN)");
  CHECK(cond("1e308*10 > x") == "test.yaml:4:13: '1e308*10 > x' is infinite");
  CHECK(cond("x < 0 || sqrt(x) > 1") == "");  // short-circuit: sqrt(x) is never evaluated
  CHECK(cond("x > 0 && sqrt(x) > 1") == "");
  CHECK(cond("x < 0 && !(sqrt(x) > 1)") == "test.yaml:4:13: 'x < 0 && !(sqrt(x) > 1)' is not a number (NaN)");
  CHECK(cond("sqrt(x) > 1 || x < 0") == "test.yaml:4:13: 'sqrt(x) > 1 || x < 0' is not a number (NaN)");
  CHECK(error_of("steps: 1\naxiom: A(-1)\nproductions:\n  - A(x) -> A(min(sqrt(x),1))\n") ==
        "test.yaml:4:15: 'min(sqrt(x),1)' is not a number (NaN)");
  CHECK(error_of("steps: 1\naxiom: A(-1)\nproductions:\n  - A(x) -> A(max(1,1e308*10))\n") ==
        "test.yaml:4:15: 'max(1,1e308*10)' is infinite");
  CHECK(error_of("steps: 1\naxiom: A(-1)\nproductions:\n  - A(x) -> A(sqrt(x)^0)\n") ==
        "test.yaml:4:15: 'sqrt(x)^0' is not a number (NaN)");
  CHECK(error_of("axiom: A(min(sqrt(-1),1))\n") == "test.yaml:1:10: 'min(sqrt(-1),1)' is not a number (NaN)");
  // A division by an infinity gave 0 (found by a probe).
  CHECK(error_of("axiom: A(1/(1e200*1e200))\n") == "test.yaml:1:10: '1/(1e200*1e200)' is infinite");
  CHECK(error_of("axiom: A(1/(sqrt(-1)))\n") == "test.yaml:1:10: '1/(sqrt(-1))' is not a number (NaN)");
  CHECK(error_of(
            "steps: 1\naxiom: A(2)\nproductions:\n  - \"A(x) : x > 1 && min(x,3) >= 2 -> B(max(x,1))\"\n") ==
        "");
}

TEST_CASE("stochastic groups must sum to 1") {
  CHECK(error_of("axiom: A\nproductions:\n  - \"A -> B : 0.5\"\n  - \"A -> C : 0.4\"\n") ==
        "test.yaml:3:15: the probabilities of the group '<A>:' sum to 0.9, not 1");
  CHECK(error_of("axiom: A\nproductions:\n  - \"A -> B : 0.5\"\n  - A -> C\n")
            .find("each needs a probability") != std::string::npos);
  CHECK(error_of("axiom: A\nproductions:\n  - \"A -> B : 1.5\"\n") ==
        "test.yaml:3:15: a probability must lie in [0, 1], got 1.5");
}

TEST_CASE("tropism within its bounds") {
  CHECK(error_of("axiom: F\ntropism: {direction: [0, 0, -1], strength: 1e300}\n") ==
        "test.yaml:2:44: tropism strength must lie in -100..100, got 1e+300");
  CHECK(error_of("axiom: F\ntropism: {direction: [1e300, 0, -1], strength: 0.2}\n") ==
        "test.yaml:2:23: a tropism direction component must lie in -1e6..1e6, got 1e+300");
  CHECK(error_of("axiom: F\ntropism: {direction: [0, 0, -1], strength: -0.5}\n") == "");
}

TEST_CASE("a key twice in a map, productions of one group apart") {
  CHECK(error_of("axiom: A\nconstants:\n  a: 1\n  b: 2\n  a: 3\n") ==
        "test.yaml:5:3: key 'a' appears twice in constants");
  // Productions of one predecessor, context and condition form one group wherever they stand.
  CHECK(error_of("axiom: A\nproductions:\n  - \"A -> B : 0.5\"\n  - \"B -> C\"\n  - \"A -> C : 0.4\"\n") ==
        "test.yaml:3:15: the probabilities of the group '<A>:' sum to 0.9, not 1");
}

TEST_CASE("invalid UTF-8 in module names (found by the fuzzer)") {
  CHECK(error_of("axiom: F\xc2\xc2\n") == "test.yaml:1:9: invalid UTF-8 in a module name");
  CHECK(error_of("axiom: F\xc3\xa9\n") == "");  // a well-formed two-byte name is fine
}

TEST_CASE("a grammar's seeds take what --seed takes, 0 to 2^64 - 1") {
  // The top-level seed stopped at 2^63 - 1 and the stand entry's refused 2^64 - 1 as not whole.
  CHECK(error_of("seed: 18446744073709551615\naxiom: F\nstand: {seed: 18446744073709551615}\n") == "");
  CHECK(grammar("seed: 18446744073709551615\naxiom: F\n").seed == 18446744073709551615ull);
  CHECK(error_of("seed: 18446744073709551616\naxiom: F\n") ==
        "test.yaml:1:7: seed must be a whole number from 0 to 18446744073709551615, got "
        "'18446744073709551616'");
  CHECK(error_of("axiom: F\nstand: {seed: -1}\n") ==
        "test.yaml:2:15: seed must be a whole number from 0 to 18446744073709551615, got '-1'");
}

TEST_CASE("control characters and look-alike spaces are not module names") {
  // Each was a module of its own, printed back as it came (a no-break space pasted from a web
  // page looks like the plain space that separates modules).
  CHECK(error_of("axiom: \"A\\u0001B\"\n") ==
        "test.yaml:1:10: character U+0001 cannot be part of a module name: a control character");
  CHECK(error_of("axiom: A\x7f\n") ==
        "test.yaml:1:9: character U+007F cannot be part of a module name: a control character");
  CHECK(error_of("axiom: A\xc2\xa0"
                 "B\n") ==
        "test.yaml:1:9: character U+00A0 cannot be part of a module name: a no-break, zero-width or other "
        "Unicode space; separate modules with plain spaces");
  CHECK(error_of("axiom: A\nproductions:\n  - \"A -> B\xe2\x80\x8b\"\n")
            .starts_with("test.yaml:3:12: character U+200B cannot be part of a module name"));
  CHECK(error_of("axiom: A\t B \xc3\xa9 \xe2\x88\x9a\n") == "");  // tabs separate; other letters are modules
}

TEST_CASE("a grammar file with a NUL byte or in UTF-16 is named at the byte, before YAML reads it") {
  const auto path = std::filesystem::temp_directory_path() / "canopy_test_bad_input_nul.yaml";
  auto load = [&](const std::string& bytes) {
    {
      std::ofstream f(path, std::ios::binary);
      f << bytes;
    }
    const std::string e = grammar_error([&] { load_grammar(path.string()); });
    return e.substr(std::min(e.size(), path.string().size()));
  };
  // yaml-cpp said "unknown escape character: B" for the first, and read past the second.
  CHECK(load(std::string("axiom: A\0B\n", 11)) ==
        ":1:9: a NUL byte: a grammar is UTF-8 text (is this a binary or corrupt file?)");
  CHECK(load(std::string("name: t\n# note\0\naxiom: A\n", 25)) ==
        ":2:7: a NUL byte: a grammar is UTF-8 text (is this a binary or corrupt file?)");
  CHECK(load(std::string("\xff\xfe"
                         "a\0x\0",
                         6)) == ":1:1: the file is UTF-16 text; a grammar is UTF-8 (save it as UTF-8)");
  CHECK(load("axiom: AB\n") == "");
  std::filesystem::remove(path);
}

TEST_CASE("errors inside productions written over lines or with escapes name their place") {
  // The place was the value's offset on the node's first line: 5:23 on a line of 16 characters.
  const std::string unknown = ": unknown name 'y': not a parameter of this production nor a constant";
  const std::string head = "steps: 1\naxiom: A(1)\nproductions:\n";
  CHECK(error_of(head + "  - >-\n    A(x) : x > 0\n    -> B(y)\n") == "test.yaml:6:10" + unknown);  // folded
  CHECK(error_of(head + "  - |-\n    A(x) : x > 0 ->\n      B(y)\n") ==
        "test.yaml:6:9" + unknown);  // literal
  CHECK(error_of(head + "  - \"A(x) : x > 0\n    -> B(y)\"\n") ==
        "test.yaml:5:10" + unknown);                                                          // "" over lines
  CHECK(error_of(head + "  - 'A(x) : x > 0\n    -> B(y)'\n") == "test.yaml:5:10" + unknown);  // '' over lines
  CHECK(error_of(head + "  - A(x) -> B(x)\n    C(y)\n") == "test.yaml:5:7" + unknown);        // plain
  // An escape is several characters of the file: \t two, \u00e9 six (two bytes of the value).
  CHECK(error_of(head + "  - \"A(x) : x > 0 -> \\tB(y)\"\n") == "test.yaml:4:26" + unknown);
  CHECK(error_of(head + "  - \"A(x) : x > 0 -> \\u00e9 B(y)\"\n") == "test.yaml:4:31" + unknown);
  CHECK(error_of(head + "  - \"A(x) : x > 0 -> \\\n    B(y)\"\n") == "test.yaml:5:7" + unknown);  // continued
  // Inside one expression too: a condition or an argument broken over lines, an escape in it.
  CHECK(error_of(head + "  - >-\n    A(x) : x > 0 &&\n    y > 1 -> B\n") == "test.yaml:6:5" + unknown);
  CHECK(error_of(head + "  - >-\n    A(x) -> B(x +\n    y)\n") == "test.yaml:6:5" + unknown);
  CHECK(error_of(head + "  - \"A(x) -> B(x +\\t y)\"\n") == "test.yaml:4:22" + unknown);
  CHECK(error_of(head + "  - >-\n    A(x) -> B(1 /\n    (x - 1))\n") ==
        "test.yaml:5:17: division by zero in '1 / (x - 1)'");  // at run time, at the '/'
}

TEST_CASE("a grammar is one YAML document") {
  // The second document's rules were read by nobody and missing from the plants, silently.
  CHECK(error_of("axiom: A\n---\nproductions:\n  - A -> B\n") ==
        "test.yaml:3:1: a second YAML document: a grammar is one document (merge it into the first, or "
        "remove the '---' that starts it)");
  CHECK(error_of("---\naxiom: A\n...\n") == "");  // markers around one document
  CHECK(error_of("axiom: A\n---\n") == "");       // a trailing marker holds nothing to miss
  CHECK(error_of("%YAML 1.2\n---\naxiom: A\n--- # a comment\n") == "");
  CHECK(error_of("axiom: A\n...\nsteps: 2\n") ==
        "test.yaml:3:1: a second YAML document: a grammar is one document (merge it into the first, or "
        "remove the '---' that starts it)");
  CHECK(error_of("axiom: A\n--- {steps: 2}\n").starts_with("test.yaml:2:5: a second YAML document"));
  // Found in the text: yaml-cpp's LoadAll never returned from this (a fuzzer's find).
  CHECK(
      error_of(", The Algorithmic Beauty of' Plants, Figure 1.24f: a N6canopy12Grammarbracketed t2ree grown "
               "from an apEx X.\nname: abop-1.24f\nsteps: 5\nangle:2Grammarbracketed t2ree gro\n  - X -> "
               "F-[e\n  internode_mX\n  - F -> FF\n") != "");
}

TEST_CASE("a list or map key with nothing after it is empty, as [] or {}") {
  // YAML reads `productions:` alone as null; it was 'productions must be a list'.
  for (const char* key : {"productions", "interpretation", "ignore", "modules", "constants", "organs"})
    CHECK(error_of(std::string("axiom: A B\n") + key + ":\n") == "");
  CHECK(error_of("axiom: A\nproductions: 3\n") == "test.yaml:2:14: productions must be a list");
  CHECK(error_of("axiom: A\nconstants: 3\n") == "test.yaml:2:12: constants must be a map");
}

TEST_CASE("production syntax") {
  CHECK(error_of("axiom: A\nproductions:\n  - A -> B : 0.5\n") ==
        "test.yaml:3:5: this production reads as a YAML map because of ': '; quote it: - \"A -> B : ...\"");
  CHECK(error_of("axiom: A\nproductions:\n  - A B\n") == "test.yaml:3:5: expected '->' in production 'A B'");
  CHECK(error_of("axiom: A\nproductions:\n  - \" -> B\"\n") ==
        "test.yaml:3:6: missing predecessor before '->'");
  CHECK(error_of("axiom: A(1)\nproductions:\n  - \"A(1) -> B\"\n") ==
        "test.yaml:3:8: a formal parameter must be a name, got '1'");
  CHECK(error_of("axiom: A(1, 2)\nproductions:\n  - \"A(x, x) -> B\"\n") ==
        "test.yaml:3:11: formal parameter 'x' appears twice in this production");
  CHECK(error_of("axiom: A\nproductions:\n  - \"[ < A -> B\"\n").find("brackets are not allowed") !=
        std::string::npos);
}

TEST_CASE("grammars that grow exponentially stop at the module cap, not out of memory") {
  const Grammar g = grammar("axiom: A\nsteps: 200\nproductions:\n  - A -> A A\n");
  CHECK_THROWS_AS(derive(g), ModuleCapError);
  // Modules of many parameters: the cap bounds the parameters too (two per module of the cap),
  // so 100 modules of 50 parameters pass a cap of 1,000 modules no more than 5,000 modules would.
  std::string wide = "B(1";
  for (int i = 1; i < 50; ++i) wide += ",1";
  wide += ")";
  const Grammar w = grammar("axiom: A\nsteps: 12\nproductions:\n  - A -> A " + wide + "\n");
  CHECK(derive(w, DeriveRequest{1, 1, 1000}).size() == 2);
  CHECK_THROWS_WITH_AS(
      derive(w, DeriveRequest{45, 1, 1000}),
      "test.yaml:4:5: the derived string exceeds the 2000 parameters the module cap of 1000 modules "
      "allows (2 per module) at step 41, as this production applied (the grammar grows too fast "
      "for this many steps; lower --steps or raise --max-modules)",
      ModuleCapError);
  CHECK_THROWS_WITH_AS(
      derive(grammar("axiom: " + wide + "\n"), DeriveRequest{0, 1, 10}),
      "test.yaml:1:8: the axiom has more than the 20 parameters the module cap of 10 modules allows "
      "(2 per module) (raise --max-modules)",
      ModuleCapError);
}

TEST_CASE("expressions nested deeper than the parser's bound are a located error, not a stack overflow") {
  const auto nested = [](const std::string& open, int n, const std::string& close) {
    std::string s;
    for (int i = 0; i < n; ++i) s += open;
    s += "1";
    for (int i = 0; i < n; ++i) s += close;
    return s;
  };
  const std::string deep =
      "expression nested too deeply (more than 256 levels of parentheses, unary operators or calls)";
  // Each of these crashed the recursive parser (a signal, not an error) past about 10,000 levels.
  for (const std::string& e : {nested("(", 30000, ")"), nested("-", 100000, ""), nested("!", 100000, ""),
                               nested("abs(", 50000, ")")}) {
    const std::string message = error_of("axiom: A(" + e + ")\n");
    CHECK(message.starts_with("test.yaml:1:"));
    CHECK(message.ends_with(deep));
  }
  CHECK(error_of("constants: {k: \"" + nested("(", 30000, ")") + "\"}\naxiom: A(k)\n").ends_with(deep));
  // '^' associates to the right: each level waits with an operand, so the operand bound speaks first.
  CHECK(error_of("axiom: A(" + nested("2^", 30000, "") + ")\n") ==
        "test.yaml:1:138: expression nested too deeply (more than 64 operands)");
  // Nesting of any depth written by hand stays well inside the bound.
  CHECK(error_of("axiom: A(" + nested("(", 200, ")") + " + " + nested("-", 200, "") + ")\n") == "");
}

TEST_CASE("steps outside 0..100000 are refused wherever they come from") {
  const Grammar g = grammar("axiom: A\nproductions:\n  - A -> A\n");
  for (const int steps : {-3, kMaxSteps + 1})
    CHECK_THROWS_WITH_AS(derive(g, DeriveRequest{steps, 1, kDefaultMaxModules}),
                         fmt::format("the derivation steps must lie in 0..100000 (got {})", steps).c_str(),
                         std::invalid_argument);
  CHECK(derived(g, kMaxSteps) == "A");
  CHECK(error_of("steps: 100001\naxiom: A\n") ==
        "test.yaml:1:8: steps must be between 0 and 100000, got 100001");
}

TEST_CASE("an organ's level of detail has the stand's range, 1..16, with its place") {
  CHECK(error_of("axiom: L(1, 1)\norgans:\n  L: {prototype: leaflet, kind: leaflet, lod: 17}\n") ==
        "test.yaml:3:47: lod must be between 1 and 16, got 17");
  CHECK(error_of("axiom: L(1, 1)\norgans:\n  L: {prototype: leaflet, kind: leaflet, lod: 16}\n") == "");
}

TEST_CASE("a file with none of a grammar's keys is not quoted back") {
  CHECK(error_of("root:x:0:0: secret\nbin: x\n") ==
        "test.yaml:1:1: not a grammar file (none of its keys is a grammar's, such as axiom or "
        "productions)");
  // A grammar with a misspelt key is still told which key.
  CHECK(error_of("axiom: F\nproduction: []\n")
            .starts_with("test.yaml:2:1: unknown key 'production' in the grammar"));
}

TEST_CASE("grammar files that are not regular files are refused before reading") {
  // /dev/zero was read until memory ran out; a folder read as an empty grammar.
  CHECK(grammar_error([] { load_grammar("/dev/zero"); }) ==
        "/dev/zero: the grammar file is not a regular file (a device, pipe or socket)");
  CHECK(grammar_error([] { load_grammar(source("grammars")); }) ==
        source("grammars") + ": the grammar file is a folder, not a file");
  CHECK_THROWS_AS(load_grammar(source("grammars/no-such-file.yaml")), GrammarFileError);
}

TEST_CASE("YAML nested past yaml-cpp's bound says so") {
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  const std::string message =
      error_of("axiom: F\nmodules: " + deep + "\n");  // was "malformed YAML: bad file"
  CHECK(message.starts_with("test.yaml:2:"));
  CHECK(message.ends_with(": malformed YAML: lists and maps nested too deeply"));
}

TEST_CASE("an organ no rule writes is a located note, and the shipped grammars have none") {
  // organs: {Lf: ...} beside productions writing L gave a stand without leaflets and no word.
  const Grammar g = grammar(
      "axiom: A\nproductions:\n  - A -> I(1, 0.1) [L(1, 1)]\ninterpretation:\n  - X -> F(1, 0.1)\n"
      "organs:\n  I: {prototype: cylinder, kind: internode}\n  Lf: {prototype: leaflet, kind: leaflet}\n"
      "  F: {prototype: cylinder, kind: internode}\n");
  REQUIRE(g.notes.size() == 1);
  CHECK(g.notes[0] ==
        "test.yaml:8:3: organ 'Lf' is written by neither the axiom nor any rule, so the plants have none (a "
        "misspelt symbol?)");
  // F, written by an interpretation rule alone, and I, by a production, have none; nor has an organ
  // only the axiom writes.
  CHECK(grammar("axiom: I(1, 0.1)\norgans:\n  I: {prototype: cylinder, kind: internode}\n").notes.empty());
  for (const char* file : {"grammars/tomato.yaml", "grammars/tomato_mature.yaml",
                           "grammars/tomato_young.yaml", "grammars/sunflower.yaml"}) {
    CAPTURE(file);
    CHECK(load_grammar(source(file)).notes.empty());
  }
}

TEST_CASE("too many distinct module names: located where the one too many stands") {
  // 65,535 names at most (brackets included): past them, the name that is one too many is named
  // at its place (here in the module list; a rule's names are located alike).
  std::string list = "modules: [";
  for (int i = 0; i < 65600; ++i) list += (i ? ", M" : "M") + std::to_string(i);
  list += "]\naxiom: M1\n";
  const std::string e = error_of(list);
  CHECK(e.starts_with("test.yaml:1:"));
  CHECK(e.find("too many distinct module names (at most 65535): 'M65533' is one more") != std::string::npos);
}

TEST_CASE("declared names that cannot be one module are refused where they are declared") {
  // A predecessor with a space became one declared name: 'A B' was rewritten as one module and
  // 'A  B' (two spaces) was not.
  CHECK(error_of("axiom: A B A  B\nproductions:\n  - A B -> C\n") ==
        "test.yaml:3:5: the predecessor 'A B' holds a space, which no module name may: a predecessor is one "
        "module (its contexts go before '<' and after '>')");
  CHECK(error_of("axiom: F\nproductions:\n  - \"B < F F > B -> X\"\n") ==
        "test.yaml:3:10: the predecessor 'F F' holds a space, which no module name may: a predecessor is one "
        "module (its contexts go before '<' and after '>')");
  CHECK(
      error_of("axiom: F[X]\nmodules: [\"X]\"]\n") ==
      "test.yaml:2:11: the module name 'X]' holds ']', which no module name may: names are one module each");
  CHECK(error_of("axiom: F\ncompound_leaf: \"[\"\n") ==
        "test.yaml:2:16: compound_leaf '[' holds '[', which no module name may: names are one module each");
  CHECK(
      error_of("axiom: F\norgans:\n  \"L,x\": {prototype: leaflet, kind: leaflet}\n") ==
      "test.yaml:3:3: the organ symbol 'L,x' holds ',', which no module name may: names are one module each");
  CHECK(
      error_of("axiom: F\nignore: [\"a b\"]\n") ==
      "test.yaml:2:10: the ignored name 'a b' holds a space, which no module name may: names are one module "
      "each");
  // Names of several characters, and a predecessor with its parameters, are as they were.
  CHECK(error_of("axiom: Leaf(1)\nproductions:\n  - \" Leaf(x) -> Leaf(x + 1)\"\n") == "");
}

TEST_CASE("a compound_leaf symbol that is also an organ is refused at both places") {
  // Its leaflets were left out of every leaf (leaf -1 in organs.csv) without a word.
  CHECK(error_of("axiom: F(1,0.1)[L(0.1,0.05)]\ncompound_leaf: L\norgans:\n  L: {prototype: leaflet, kind: "
                 "leaflet}\n  F: {prototype: cylinder, kind: internode}\n") ==
        "test.yaml:2:16: compound_leaf 'L' is also an organ (test.yaml:4:3): the symbol that begins a "
        "compound leaf "
        "emits no organ; give it a name of its own, before the leaf's organs");
}

TEST_CASE("tropism: and stand: with nothing after them are the empty map") {
  const Grammar none = grammar("axiom: F\ntropism:\nstand:\n"),
                empty = grammar("axiom: F\ntropism: {}\nstand: {}\n");
  REQUIRE(none.tropism.has_value() == empty.tropism.has_value());
  REQUIRE(none.stand.has_value() == empty.stand.has_value());
  CHECK(error_of("axiom: F\ntropism: 3\n") == "test.yaml:2:10: tropism must be a map");
}

TEST_CASE("a stand entry's lengths past the plants' reach are refused at their place") {
  // They were refused later naming --plant-spacing or --jitter, which the user had not given.
  CHECK(error_of("axiom: F\nstand: {rows: 2, per_row: 2, plant_spacing: 1e300}\n") ==
        "test.yaml:2:45: plant_spacing is 1e+300 m: plants may stand at most 1e+08 m from the origin");
  CHECK(error_of("axiom: F\nstand:\n  jitter: 1e9\n") ==
        "test.yaml:3:11: jitter is 1e+09 m: plants may stand at most 1e+08 m from the origin");
  CHECK(error_of("axiom: F\nstand: {row_spacing: 1e8}\n") == "");  // the bound itself
}

TEST_CASE("YAML core-schema scalars: a leading + and True/False are taken as YAML readers take them") {
  const Grammar g =
      grammar("axiom: F\nsteps: +3\nstand: {plant_spacing: +0.5, random_rotation: True, jitter: .5}\n");
  CHECK(g.steps == 3);
  REQUIRE(g.stand.has_value());
  CHECK(*g.stand->plant_spacing == 0.5);
  CHECK(*g.stand->random_rotation);
  CHECK(grammar("axiom: F\nstand: {random_rotation: FALSE}\n").stand->random_rotation == false);
  CHECK(parse_override("k=+2").value == 2);
  // A sign of its own is still no number.
  CHECK(error_of("axiom: F\nstand: {plant_spacing: +-0.5}\n") ==
        "test.yaml:2:24: plant_spacing must be a finite number, got '+-0.5'");
  CHECK(error_of("axiom: F\nstand: {random_rotation: Truth}\n") ==
        "test.yaml:2:26: random_rotation must be true or false");
}

TEST_CASE(
    "messages that name the real cause: a number out of range, an unclosed '(', rand() in a probability") {
  CHECK(error_of("axiom: A(1e400)\n") ==
        "test.yaml:1:10: number '1e400' is out of a double's range (about 1e-308 to 1e308 in size)");
  CHECK(error_of("axiom: A\nproductions:\n  - \"A(x -> A(x)\"\n") ==
        "test.yaml:3:7: this '(' is never closed");
  CHECK(
      error_of("axiom: A\nproductions:\n  - \"A -> B : rand(0,1)\"\n") ==
      "test.yaml:3:15: rand() cannot be used here: only in a production's condition or successor and in the "
      "axiom (not in a constant or a probability)");
}
