// libFuzzer target: any bytes as a grammar file. Located errors are the expected way out;
// anything else (a crash, a sanitizer report, another exception) is a bug.
#include "lsystem/derive.hpp"
#include "lsystem/grammar.hpp"
#include "lsystem/module_format.hpp"

#include <algorithm>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const canopy::Grammar g = canopy::parse_grammar(text, "fuzz.yaml");
    canopy::DeriveRequest req;
    req.steps = std::min(g.steps, 8);
    req.max_modules = 20000;
    const canopy::ModuleString s = canopy::derive(g, req);
    const canopy::ModuleString t = canopy::interpret(g, s, g.seed, 20000);
    (void)canopy::format_modules(g, t);
    (void)canopy::stats_json(g, s);
  } catch (const canopy::GrammarError&) {
  } catch (const canopy::ModuleCapError&) {
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
