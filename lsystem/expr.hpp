#pragma once
/// Expressions of the grammar language (ABOP ch. 1.10 "parametric L-systems"): numbers, names,
/// + - * / ^, comparisons, && || !, sin cos tan sqrt abs min max floor ceil, rand(a,b).
/// Compiled once to a small stack program; evaluation allocates nothing.
#include "lsystem/error.hpp"
#include "lsystem/rng.hpp"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace canopy {

enum class Op : std::uint8_t {
  Const,
  Param,
  Neg,
  Not,
  Add,
  Sub,
  Mul,
  Div,
  Pow,
  Lt,
  Gt,
  Le,
  Ge,
  Eq,
  Ne,
  AndJump,  // top == 0: keep 0 and jump; else pop
  OrJump,   // top != 0: replace by 1 and jump; else pop
  ToBool,
  Sin,
  Cos,
  Tan,
  Sqrt,
  Abs,
  Min,
  Max,
  Floor,
  Ceil,
  Rand,
};

struct Instr {
  Op op;
  std::uint32_t arg = 0;  // parameter slot, jump target or argument count
  double value = 0;       // Const
  int column = 0;         // offset in the expression text, for errors
};

/// What a name in an expression stands for: a formal parameter slot or a constant value.
struct NameRef {
  bool is_param = false;
  int slot = 0;
  double value = 0;
};
using NameResolver = std::function<std::optional<NameRef>(std::string_view)>;

/// A compiled expression. Trig functions take radians; `pi` is a built-in constant.
class Expr {
 public:
  Expr() = default;
  /// Where character k of an expression's text is in the file.
  using Place = std::function<SourcePos(std::size_t)>;
  /// Compiles `text`, found at `pos` in the grammar file; names are looked up with `resolve`.
  /// `place`, where given, says where each character is (an expression written over lines or
  /// with escapes in a YAML string is not its first character's line shifted).
  static Expr compile(std::string_view text, const SourcePos& pos, const NameResolver& resolve,
                      const Place& place = {});
  /// A literal value.
  static Expr constant(double v, const SourcePos& pos = {});

  /// Evaluates with `frame` holding the bound parameters; throws GrammarError (division by zero,
  /// a NaN or infinite result) naming the expression's place.
  double eval(const double* frame, Rng& rng) const;
  /// Evaluation for expressions with no parameters and no rand().
  double eval_constant() const;

  bool is_constant() const { return code_.size() == 1 && code_[0].op == Op::Const; }
  bool uses_rand() const { return uses_rand_; }
  const SourcePos& pos() const { return pos_; }
  /// Where character k of the text is in the file.
  SourcePos place(std::size_t k) const;
  const std::string& text() const { return text_; }

 private:
  friend class ExprParser;
  double run(const double* frame, Rng* rng) const;
  std::vector<Instr> code_;
  SourcePos pos_;
  std::string text_;
  std::vector<std::pair<int, int>> places_;  // line, column per character; empty: pos_ shifted
  int max_stack_ = 0;
  bool uses_rand_ = false;
};

}  // namespace canopy
