// grammar_digest: the same document in another style gives the same digest; any other change,
// another.
#include "lsystem/error.hpp"
#include "lsystem/grammar.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>

using namespace canopy;

namespace {

/// The digest of `text` written to a temporary file.
std::string digest_of(const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / "canopy_test_grammar_digest.yaml";
  std::ofstream(path) << text;
  std::string d = grammar_digest(path.string());
  std::filesystem::remove(path);
  return d;
}

const char* kBlock =
    "# a comment\n"
    "name: t\n"
    "axiom: A(1)\n"
    "steps: 3\n"
    "productions:\n"
    "  - A(x) -> I(0.1, 0.01) [ A(x) ]\n"
    "organs:\n"
    "  I: {prototype: cylinder, kind: internode}\n";

}  // namespace

TEST_CASE("grammar_digest: comments, spacing, quoting and style change nothing") {
  const std::string d = digest_of(kBlock);
  CHECK(d.size() == 16);
  CHECK(digest_of(kBlock) == d);
  CHECK(digest_of(std::string(kBlock) + "\n# another comment\n\n") == d);
  CHECK(digest_of("name: t   # a comment after a value\n\n"
                  "axiom: \"A(1)\"\n"
                  "steps: '3'\n"
                  "productions: [\"A(x) -> I(0.1, 0.01) [ A(x) ]\"]\n"
                  "organs:\n"
                  "    I:\n"
                  "        prototype: cylinder\n"
                  "        kind: internode\n") == d);
}

TEST_CASE("grammar_digest: a value, a key, an entry or the order of keys changes it") {
  const std::string d = digest_of(kBlock);
  const auto edited = [](const std::string& from, const std::string& to) {
    std::string t = kBlock;
    t.replace(t.find(from), from.size(), to);
    return t;
  };
  CHECK(digest_of(edited("steps: 3", "steps: 4")) != d);
  CHECK(digest_of(edited("steps: 3", "steps: 3.0")) != d);  // values as written: no numeric reading
  CHECK(digest_of(edited("I(0.1, 0.01)", "I(0.1, 0.02)")) != d);
  CHECK(digest_of(edited("name: t\n", "")) != d);
  CHECK(digest_of(edited("name: t\naxiom: A(1)\n", "axiom: A(1)\nname: t\n")) != d);
  CHECK(digest_of(edited("  - A(x)", "  - B(x) -> B(x)\n  - A(x)")) != d);
  // A scalar and a one-item list of it, or a key and its value run together, are told apart.
  CHECK(digest_of("a: [x]\n") != digest_of("a: x\n"));
  CHECK(digest_of("ab: c\n") != digest_of("a: bc\n"));
}

TEST_CASE("grammar_digest: errors name the file") {
  const auto path = std::filesystem::temp_directory_path() / "canopy_test_grammar_digest_bad.yaml";
  std::ofstream(path) << "name: t\naxiom: [unclosed\n";
  try {
    grammar_digest(path.string());
    FAIL("malformed YAML gave a digest");
  } catch (const GrammarError& e) {
    CHECK(std::string(e.what()).find(path.string() + ":") == 0);
    CHECK(std::string(e.what()).find("malformed YAML") != std::string::npos);
  }
  std::filesystem::remove(path);
  CHECK_THROWS_AS(grammar_digest(path.string()), GrammarFileError);
}
