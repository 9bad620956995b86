#include "lsystem/expr.hpp"

#include <array>
#include <cctype>
#include <charconv>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace canopy {
namespace {

constexpr int kMaxStack = 64;

/// How deeply parentheses, unary operators, function calls and right-associated '^' may nest in
/// one expression. The parser recurses once per level (three frames of a few hundred bytes), so
/// a bound far below what any stack holds turns 30,000 '(' into a located error instead of a
/// stack overflow; no grammar written by hand comes near it.
constexpr int kMaxNesting = 256;

struct Function {
  std::string_view name;
  Op op;
  int min_args, max_args;
};
constexpr std::array<Function, 10> kFunctions{{
    {"sin", Op::Sin, 1, 1},
    {"cos", Op::Cos, 1, 1},
    {"tan", Op::Tan, 1, 1},
    {"sqrt", Op::Sqrt, 1, 1},
    {"abs", Op::Abs, 1, 1},
    {"floor", Op::Floor, 1, 1},
    {"ceil", Op::Ceil, 1, 1},
    {"min", Op::Min, 2, 16},
    {"max", Op::Max, 2, 16},
    {"rand", Op::Rand, 2, 2},
}};

}  // namespace

/// Recursive-descent (precedence climbing) compiler from text to the stack program.
class ExprParser {
 public:
  ExprParser(std::string_view text, const SourcePos& pos, const NameResolver& resolve, Expr& out)
      : s_(text), pos_(pos), resolve_(resolve), out_(out) {}

  void parse() {
    skip();
    if (at_end()) error(0, "empty expression");
    binary(1);
    skip();
    if (!at_end()) error(i_, "unexpected '{}' in expression", s_[i_]);
  }

 private:
  template <typename... A>
  [[noreturn]] void error(std::size_t at, fmt::format_string<A...> f, A&&... a) {
    throw GrammarError(out_.place(at), fmt::format(f, std::forward<A>(a)...));
  }
  bool at_end() const { return i_ >= s_.size(); }
  void skip() {
    while (!at_end() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }
  bool eat(std::string_view tok) {
    skip();
    if (s_.substr(i_, tok.size()) == tok) {
      i_ += tok.size();
      return true;
    }
    return false;
  }
  void emit(Op op, std::size_t col, int stack_delta, std::uint32_t arg = 0, double value = 0) {
    out_.code_.push_back({op, arg, value, static_cast<int>(col)});
    depth_ += stack_delta;
    if (depth_ > kMaxStack) error(col, "expression nested too deeply (more than {} operands)", kMaxStack);
    out_.max_stack_ = std::max(out_.max_stack_, depth_);
  }

  struct BinOp {
    std::string_view tok;
    int prec;
    Op op;
  };
  // Longest tokens first so "<=" is not read as "<".
  static constexpr std::array<BinOp, 14> kBinOps{{
      {"||", 1, Op::OrJump},
      {"&&", 2, Op::AndJump},
      {"==", 3, Op::Eq},
      {"!=", 3, Op::Ne},
      {"<=", 4, Op::Le},
      {">=", 4, Op::Ge},
      {"<", 4, Op::Lt},
      {">", 4, Op::Gt},
      {"+", 5, Op::Add},
      {"-", 5, Op::Sub},
      {"*", 6, Op::Mul},
      {"/", 6, Op::Div},
      {"^", 8, Op::Pow},
      {"=", 0, Op::Eq},
  }};

  const BinOp* peek_binop() {
    skip();
    for (const auto& b : kBinOps)
      if (s_.substr(i_, b.tok.size()) == b.tok) return &b;
    return nullptr;
  }

  /// Counts one level of nesting while it lives (see kMaxNesting).
  struct Nest {
    ExprParser& p;
    Nest(ExprParser& parser, std::size_t at) : p(parser) {
      if (++p.nesting_ > kMaxNesting)
        p.error(at,
                "expression nested too deeply (more than {} levels of parentheses, unary operators or calls)",
                kMaxNesting);
    }
    ~Nest() { --p.nesting_; }
  };

  void binary(int min_prec) {
    const Nest nest(*this, i_);
    unary();
    for (;;) {
      const BinOp* b = peek_binop();
      if (b && b->prec == 0) error(i_, "'=' is not an operator; use '==' to compare");
      if (!b || b->prec < min_prec) return;
      const std::size_t col = i_;
      i_ += b->tok.size();
      if (b->op == Op::AndJump || b->op == Op::OrJump) {
        const std::size_t jump_at = out_.code_.size();
        emit(b->op, col, -1);  // pops when it falls through
        binary(b->prec + 1);
        emit(Op::ToBool, col, 0);
        out_.code_[jump_at].arg = static_cast<std::uint32_t>(out_.code_.size());
        continue;
      }
      // '^' is right-associative; the others associate to the left.
      binary(b->op == Op::Pow ? b->prec : b->prec + 1);
      emit(b->op, col, -1);
    }
  }

  void unary() {
    skip();
    const std::size_t col = i_;
    if (eat("-")) {
      binary(7);
      emit(Op::Neg, col, 0);
    } else if (eat("+")) {
      binary(7);
    } else if (!at_end() && s_[i_] == '!' && s_.substr(i_, 2) != "!=") {
      ++i_;
      binary(7);
      emit(Op::Not, col, 0);
    } else {
      primary();
    }
  }

  void primary() {
    skip();
    if (at_end()) error(i_, "expression ends where a value was expected");
    const std::size_t col = i_;
    const char c = s_[i_];
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') return number();
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') return name();
    if (eat("(")) {
      binary(1);
      if (!eat(")"))
        error(i_, "expected ')' to close the '(' at column {}", pos_.column + static_cast<int>(col));
      return;
    }
    error(col, "unexpected '{}' where a value was expected", c);
  }

  void number() {
    const std::size_t start = i_;
    while (!at_end() && (std::isdigit(static_cast<unsigned char>(s_[i_])) || s_[i_] == '.')) ++i_;
    if (!at_end() && (s_[i_] == 'e' || s_[i_] == 'E')) {
      std::size_t j = i_ + 1;
      if (j < s_.size() && (s_[j] == '+' || s_[j] == '-')) ++j;
      if (j < s_.size() && std::isdigit(static_cast<unsigned char>(s_[j]))) {
        i_ = j;
        while (!at_end() && std::isdigit(static_cast<unsigned char>(s_[i_]))) ++i_;
      }
    }
    double v = 0;
    const auto r = std::from_chars(s_.data() + start, s_.data() + i_, v);
    if (r.ec == std::errc::result_out_of_range && r.ptr == s_.data() + i_)
      error(start, "number '{}' is out of a double's range (about 1e-308 to 1e308 in size)",
            s_.substr(start, i_ - start));
    if (r.ec != std::errc() || r.ptr != s_.data() + i_)
      error(start, "malformed number '{}'", s_.substr(start, i_ - start));
    emit(Op::Const, start, 1, 0, v);
  }

  void name() {
    const std::size_t start = i_;
    while (!at_end() && (std::isalnum(static_cast<unsigned char>(s_[i_])) || s_[i_] == '_')) ++i_;
    const std::string_view id = s_.substr(start, i_ - start);
    skip();
    if (!at_end() && s_[i_] == '(') return call(id, start);
    if (auto ref = resolve_ ? resolve_(id) : std::nullopt) {
      if (ref->is_param) emit(Op::Param, start, 1, static_cast<std::uint32_t>(ref->slot));
      else emit(Op::Const, start, 1, 0, ref->value);
      return;
    }
    if (id == "pi") return emit(Op::Const, start, 1, 0, std::numbers::pi);
    for (const auto& f : kFunctions)
      if (f.name == id) error(start, "function '{}' needs arguments in parentheses", id);
    error(start, "unknown name '{}': not a parameter of this production nor a constant", id);
  }

  void call(std::string_view id, std::size_t start) {
    const Function* fn = nullptr;
    for (const auto& f : kFunctions)
      if (f.name == id) fn = &f;
    if (!fn) error(start, "unknown function '{}' (known: sin cos tan sqrt abs min max floor ceil rand)", id);
    eat("(");
    int args = 0;
    skip();
    if (!eat(")")) {
      for (;;) {
        binary(1);
        ++args;
        if (eat(")")) break;
        if (!eat(",")) error(i_, "expected ',' or ')' in the arguments of '{}'", id);
      }
    }
    if (args < fn->min_args || args > fn->max_args) {
      if (fn->min_args == fn->max_args)
        error(start, "'{}' takes {} argument(s), got {}", id, fn->min_args, args);
      error(start, "'{}' takes at least {} arguments, got {}", id, fn->min_args, args);
    }
    if (fn->op == Op::Rand) out_.uses_rand_ = true;
    emit(fn->op, start, 1 - args, static_cast<std::uint32_t>(args));
  }

  std::string_view s_;
  std::size_t i_ = 0;
  int depth_ = 0;
  int nesting_ = 0;
  SourcePos pos_;
  const NameResolver& resolve_;
  Expr& out_;
};

SourcePos Expr::place(std::size_t k) const {
  if (places_.empty()) return pos_.shifted(static_cast<int>(k));
  const auto& [line, column] = places_[std::min(k, places_.size() - 1)];
  return {pos_.file, line, column};
}

Expr Expr::compile(std::string_view text, const SourcePos& pos, const NameResolver& resolve,
                   const Place& place) {
  Expr e;
  e.pos_ = pos;
  e.text_ = std::string(text);
  if (place) {
    // Kept only where some character is not on the first one's line at its offset.
    bool shifted = true;
    std::vector<std::pair<int, int>> places(text.size() + 1);
    for (std::size_t k = 0; k <= text.size(); ++k) {
      const SourcePos p = place(k);
      places[k] = {p.line, p.column};
      shifted = shifted && p.line == pos.line && p.column == pos.column + static_cast<int>(k);
    }
    if (!shifted) e.places_ = std::move(places);
  }
  ExprParser(text, pos, resolve, e).parse();
  bool has_params = false;
  for (const auto& in : e.code_) has_params |= in.op == Op::Param;
  if (!has_params && !e.uses_rand_ && e.code_.size() > 1) {
    const double v = e.eval_constant();  // folds, reporting division by zero at load time
    e.code_ = {{Op::Const, 0, v, 0}};
    e.max_stack_ = 1;
  }
  return e;
}

Expr Expr::constant(double v, const SourcePos& pos) {
  Expr e;
  e.pos_ = pos;
  e.code_ = {{Op::Const, 0, v, 0}};
  e.max_stack_ = 1;
  return e;
}

double Expr::eval(const double* frame, Rng& rng) const { return run(frame, &rng); }

double Expr::eval_constant() const { return run(nullptr, nullptr); }

namespace {

// A NaN or an infinity is an error at the expression's place (docs/grammar.md), found by the check
// of the result: so the operations that would hide one (a comparison, && || !, min and max, pow
// with a 0 exponent, rand's bounds, a division by one) carry it on instead, NaN if either operand is NaN, else inf.
double bad(double a, double b = 0) {
  return std::isnan(a) || std::isnan(b) ? std::numeric_limits<double>::quiet_NaN()
                                        : std::numeric_limits<double>::infinity();
}
double compared(double a, double b, bool answer) {
  return std::isfinite(a) && std::isfinite(b) ? (answer ? 1 : 0) : bad(a, b);
}

}  // namespace

double Expr::run(const double* frame, Rng* rng) const {
  if (code_.size() == 1 && code_[0].op == Op::Const) return code_[0].value;
  double st[kMaxStack + 1];
  int sp = -1;
  const std::size_t n = code_.size();
  for (std::size_t pc = 0; pc < n; ++pc) {
    const Instr& in = code_[pc];
    switch (in.op) {
      case Op::Const: st[++sp] = in.value; break;
      case Op::Param: st[++sp] = frame[in.arg]; break;
      case Op::Neg: st[sp] = -st[sp]; break;
      case Op::Not: st[sp] = std::isfinite(st[sp]) ? (st[sp] == 0 ? 1 : 0) : bad(st[sp]); break;
      case Op::ToBool: st[sp] = std::isfinite(st[sp]) ? (st[sp] != 0 ? 1 : 0) : bad(st[sp]); break;
      case Op::Add:
        --sp;
        st[sp] += st[sp + 1];
        break;
      case Op::Sub:
        --sp;
        st[sp] -= st[sp + 1];
        break;
      case Op::Mul:
        --sp;
        st[sp] *= st[sp + 1];
        break;
      case Op::Div:
        --sp;
        if (st[sp + 1] == 0) fail_at(place(static_cast<std::size_t>(in.column)), "division by zero in '{}'", text_);
        st[sp] = std::isfinite(st[sp + 1]) ? st[sp] / st[sp + 1] : bad(st[sp], st[sp + 1]);  // x / inf hides it
        break;
      case Op::Pow:
        --sp;
        st[sp] = std::isfinite(st[sp]) && std::isfinite(st[sp + 1]) ? std::pow(st[sp], st[sp + 1])
                                                                    : bad(st[sp], st[sp + 1]);
        break;
      case Op::Lt:
        --sp;
        st[sp] = compared(st[sp], st[sp + 1], st[sp] < st[sp + 1]);
        break;
      case Op::Gt:
        --sp;
        st[sp] = compared(st[sp], st[sp + 1], st[sp] > st[sp + 1]);
        break;
      case Op::Le:
        --sp;
        st[sp] = compared(st[sp], st[sp + 1], st[sp] <= st[sp + 1]);
        break;
      case Op::Ge:
        --sp;
        st[sp] = compared(st[sp], st[sp + 1], st[sp] >= st[sp + 1]);
        break;
      case Op::Eq:
        --sp;
        st[sp] = compared(st[sp], st[sp + 1], st[sp] == st[sp + 1]);
        break;
      case Op::Ne:
        --sp;
        st[sp] = compared(st[sp], st[sp + 1], st[sp] != st[sp + 1]);
        break;
      case Op::AndJump:
        if (!std::isfinite(st[sp])) {
          st[sp] = bad(st[sp]);
          pc = in.arg - 1;
        } else if (st[sp] == 0) pc = in.arg - 1;
        else --sp;
        break;
      case Op::OrJump:
        if (!std::isfinite(st[sp]) || st[sp] != 0) {
          st[sp] = std::isfinite(st[sp]) ? 1 : bad(st[sp]);
          pc = in.arg - 1;
        } else --sp;
        break;
      case Op::Sin: st[sp] = std::sin(st[sp]); break;
      case Op::Cos: st[sp] = std::cos(st[sp]); break;
      case Op::Tan: st[sp] = std::tan(st[sp]); break;
      case Op::Sqrt: st[sp] = std::sqrt(st[sp]); break;
      case Op::Abs: st[sp] = std::fabs(st[sp]); break;
      case Op::Floor: st[sp] = std::floor(st[sp]); break;
      case Op::Ceil: st[sp] = std::ceil(st[sp]); break;
      case Op::Min:
      case Op::Max: {
        const int k = static_cast<int>(in.arg);
        double m = st[sp - k + 1];
        for (int j = 1; j < k; ++j) {
          const double v = st[sp - k + 1 + j];
          m = std::isfinite(m) && std::isfinite(v) ? (in.op == Op::Min ? std::fmin(m, v) : std::fmax(m, v))
                                                   : bad(m, v);
        }
        sp -= k - 1;
        st[sp] = m;
        break;
      }
      case Op::Rand: {
        if (!rng)
          fail_at(place(static_cast<std::size_t>(in.column)),
                  "rand() cannot be used here: only in a production's condition or successor and in the "
                  "axiom (not in a constant or a probability)");
        --sp;
        st[sp] = std::isfinite(st[sp]) && std::isfinite(st[sp + 1]) ? rng->uniform(st[sp], st[sp + 1])
                                                                    : bad(st[sp], st[sp + 1]);
        break;
      }
    }
  }
  const double r = st[0];
  if (std::isnan(r)) fail_at(pos_, "'{}' is not a number (NaN)", text_);
  if (std::isinf(r)) fail_at(pos_, "'{}' is infinite", text_);
  return r;
}

}  // namespace canopy
