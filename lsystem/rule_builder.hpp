#pragma once
/// Compiles the text of module lists and productions into symbols, expressions and rule groups,
/// tracking each module's parameter count (one count per name throughout a file).
#include "lsystem/grammar.hpp"
#include "lsystem/production_syntax.hpp"

#include <functional>
#include <string>
#include <vector>

namespace canopy {

class RuleBuilder {
 public:
  using Locate = std::function<SourcePos(std::size_t)>;
  struct Source {
    std::string text;
    Locate locate;  // offset in `text` -> place in the file
  };

  RuleBuilder(Grammar& g, ModuleLexer lexer);

  /// A module list whose arguments are expressions of the grammar's constants (and rand).
  std::vector<SuccessorModule> module_list(std::string_view text, const Locate& locate,
                                           std::string_view what);
  /// Throws unless every `[` has its `]` in `modules`.
  void check_brackets(const std::vector<SuccessorModule>& modules, const SourcePos& where,
                      std::string_view what);
  /// Productions in file order, grouped into stochastic groups, with each symbol's rewrite mode.
  RuleTable rule_table(const std::vector<Source>& sources, std::string_view what);
  /// Turtle symbols take at most one parameter (`|` `$` `[` `]` none), unless declared organs.
  void check_turtle_arities(const std::map<Symbol, OrganEntry>& organs);

  /// Records a use of `s` with `n` parameters; throws if an earlier use had another count.
  void note_arity(Symbol s, int n, const SourcePos& pos);
  /// Where `s` was first used with parameters counted, if it was.
  const SourcePos* first_use(Symbol s) const;

 private:
  std::vector<SuccessorModule> compile_modules(std::string_view text, const Locate& locate, std::size_t base,
                                               const NameResolver& resolve);
  std::vector<ModulePattern> patterns(std::string_view text, const Locate& locate, std::size_t base,
                                      std::vector<std::string>& formals);
  NameResolver resolver(const std::vector<std::string>* formals) const;

  Grammar& g_;
  ModuleLexer lexer_;
  std::vector<SourcePos> first_use_;
  std::vector<char> seen_;
};

}  // namespace canopy
