#include "lsystem/rule_builder.hpp"

#include <cctype>
#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_map>

namespace canopy {
namespace {

bool is_identifier(std::string_view s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  for (char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  return true;
}

std::string squeeze(std::string_view s) {
  std::string out;
  for (char c : s)
    if (!std::isspace(static_cast<unsigned char>(c))) out += c;
  return out;
}

/// `text` (a condition) without white space and with each formal parameter written as its slot
/// ("$0", "$1", ...): `x > 0` of A(x) and `y > 0` of A(y) are one condition.
std::string canonical_condition(std::string_view text, const std::vector<std::string>& formals) {
  std::string out;
  const auto word = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  for (std::size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
    } else if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') {  // a number, exponent and all
      const std::size_t b = i++;
      while (i < text.size() && (word(text[i]) || text[i] == '.' ||
                                 ((text[i] == '+' || text[i] == '-') && (text[i - 1] == 'e' || text[i - 1] == 'E'))))
        ++i;
      out += text.substr(b, i - b);
    } else if (word(c)) {
      const std::size_t b = i;
      while (i < text.size() && word(text[i])) ++i;
      const std::string_view name = text.substr(b, i - b);
      // A name before '(' is a function (as the expression reads it), whatever a formal is called.
      std::size_t after = i;
      while (after < text.size() && std::isspace(static_cast<unsigned char>(text[after]))) ++after;
      const bool call = after < text.size() && text[after] == '(';
      const auto f = call ? formals.end() : std::find(formals.begin(), formals.end(), name);
      out += f == formals.end() ? std::string(name) : "$" + std::to_string(f - formals.begin());
    } else {
      out += c, ++i;
    }
  }
  return out;
}

}  // namespace

RuleBuilder::RuleBuilder(Grammar& g, ModuleLexer lexer) : g_(g), lexer_(std::move(lexer)) {}

void RuleBuilder::note_arity(Symbol s, int n, const SourcePos& pos) {
  if (first_use_.size() <= s) {
    first_use_.resize(s + 1u);
    seen_.resize(s + 1u, 0);
  }
  const int known = g_.symbols.arity(s);
  if (known >= 0 && known != n) {
    const std::string where = seen_[s] ? fmt::format(" at {}", first_use_[s].str()) : std::string();
    fail_at(pos,
            "module '{}' is used with {} parameter(s) here but with {}{}; a name has one parameter count",
            g_.symbols.name(s), n, known, where);
  }
  g_.symbols.set_arity(s, n);
  if (!seen_[s]) {
    seen_[s] = 1;
    first_use_[s] = pos;
  }
}

const SourcePos* RuleBuilder::first_use(Symbol s) const {
  return s < seen_.size() && seen_[s] ? &first_use_[s] : nullptr;
}

NameResolver RuleBuilder::resolver(const std::vector<std::string>* formals) const {
  return [this, formals](std::string_view name) -> std::optional<NameRef> {
    if (formals)
      for (std::size_t i = 0; i < formals->size(); ++i)
        if ((*formals)[i] == name) return NameRef{true, static_cast<int>(i), 0};
    for (const auto& [n, v] : g_.constants)
      if (n == name) return NameRef{false, 0, v};
    return std::nullopt;
  };
}

std::vector<SuccessorModule> RuleBuilder::compile_modules(std::string_view text, const Locate& locate,
                                                          std::size_t base, const NameResolver& resolve) {
  std::vector<SuccessorModule> out;
  for (const RawModule& raw : lexer_.lex(text, locate(base))) {
    SuccessorModule m;
    m.pos = locate(base + raw.offset);
    m.symbol = g_.symbols.intern(raw.name, m.pos);
    note_arity(m.symbol, static_cast<int>(raw.args.size()), m.pos);
    for (const auto& a : raw.args) {
      const std::size_t lead = leading_blanks(a.text);
      const std::size_t at = base + a.offset + lead;
      m.args.push_back(Expr::compile(trim(a.text), locate(at), resolve,
                                     [&locate, at](std::size_t k) { return locate(at + k); }));
    }
    out.push_back(std::move(m));
  }
  return out;
}

std::vector<SuccessorModule> RuleBuilder::module_list(std::string_view text, const Locate& locate,
                                                      std::string_view) {
  return compile_modules(text, locate, 0, resolver(nullptr));
}

void RuleBuilder::check_brackets(const std::vector<SuccessorModule>& modules, const SourcePos& where,
                                 std::string_view what) {
  std::vector<const SuccessorModule*> open;
  for (const auto& m : modules) {
    if (m.symbol == g_.symbols.open_bracket()) open.push_back(&m);
    else if (m.symbol == g_.symbols.close_bracket()) {
      if (open.empty()) fail_at(m.pos, "unbalanced brackets in {}: ']' closes no '['", what);
      open.pop_back();
    }
  }
  if (!open.empty()) fail_at(open.back()->pos, "unbalanced brackets in {}: this '[' is never closed", what);
  (void)where;
}

std::vector<ModulePattern> RuleBuilder::patterns(std::string_view text, const Locate& locate,
                                                 std::size_t base, std::vector<std::string>& formals) {
  std::vector<ModulePattern> out;
  for (const RawModule& raw : lexer_.lex(text, locate(base))) {
    ModulePattern p;
    p.pos = locate(base + raw.offset);
    p.symbol = g_.symbols.intern(raw.name, p.pos);
    p.first_slot = static_cast<int>(formals.size());
    if (p.symbol == g_.symbols.open_bracket() || p.symbol == g_.symbols.close_bracket())
      fail_at(p.pos,
              "brackets are not allowed in a predecessor or context (contexts skip branches by themselves)");
    note_arity(p.symbol, static_cast<int>(raw.args.size()), p.pos);
    for (const auto& a : raw.args) {
      const std::string_view name = trim(a.text);
      const SourcePos at = locate(base + a.offset + leading_blanks(a.text));
      if (!is_identifier(name)) fail_at(at, "a formal parameter must be a name, got '{}'", name);
      for (const auto& f : formals)
        if (f == name) fail_at(at, "formal parameter '{}' appears twice in this production", name);
      formals.emplace_back(name);
    }
    out.push_back(p);
  }
  return out;
}

RuleTable RuleBuilder::rule_table(const std::vector<Source>& sources, std::string_view what) {
  RuleTable t;
  std::vector<std::vector<bool>> explicit_prob;  // per group, per successor
  std::vector<std::vector<SourcePos>> prob_pos;
  // Group by key through a map: a linear search made loading quadratic in the productions (200,000
  // of them took 117 s).
  std::unordered_map<std::string, int> group_of;
  for (const Source& src : sources) {
    const std::string_view text = src.text;
    const ProductionParts parts = split_production(text, src.locate(0));
    std::vector<std::string> formals;
    RuleGroup group;
    group.pos = src.locate(parts.predecessor.begin);
    auto context = [&](const Span& s) -> std::vector<ModulePattern> {
      if (!s.present || s.of(text) == "*") return {};
      if (s.begin == s.end)
        fail_at(src.locate(s.begin), "empty context; write '*' for any context or leave out '<' / '>'");
      return patterns(s.of(text), src.locate, s.begin, formals);
    };
    group.left = context(parts.left);
    const auto pred = patterns(parts.predecessor.of(text), src.locate, parts.predecessor.begin, formals);
    if (pred.size() != 1)
      fail_at(group.pos, "the predecessor must be one module, got {} in '{}'", pred.size(),
              parts.predecessor.of(text));
    group.predecessor = pred[0];
    group.right = context(parts.right);
    group.frame_size = static_cast<int>(formals.size());
    if (group.frame_size > kMaxFrame)
      fail_at(group.pos, "a production binds {} formal parameters; at most {} are supported",
              group.frame_size, kMaxFrame);
    const NameResolver resolve = resolver(&formals);
    if (parts.condition.present) {
      const std::size_t at = parts.condition.begin;
      group.condition = Expr::compile(parts.condition.of(text), src.locate(at), resolve,
                                      [&src, at](std::size_t k) { return src.locate(at + k); });
      if (group.condition->is_constant() && group.condition->eval_constant() == 0) {
        // A condition that is always false is legal; it simply never applies.
      }
    }
    group.key = squeeze(parts.left.of(text)) + "<" + squeeze(parts.predecessor.of(text)) + ">" +
                squeeze(parts.right.of(text)) + ":" + squeeze(parts.condition.of(text));
    // What makes productions one group: the modules matched (symbol and parameter count, the
    // names of the formals aside; a context left out and '*' alike), then the condition with
    // its formals by slot. The frame's slots are positional, so a group's successors each read
    // the parameters they name.
    std::string same;
    {
      std::vector<const ModulePattern*> all;
      for (const auto& p : group.left) all.push_back(&p);
      all.push_back(&group.predecessor);
      for (const auto& p : group.right) all.push_back(&p);
      const std::size_t pred_at = group.left.size();
      for (std::size_t k = 0; k < all.size(); ++k) {
        const int end = k + 1 < all.size() ? all[k + 1]->first_slot : group.frame_size;
        if (k == pred_at) same += '<';
        same += std::to_string(all[k]->symbol) + "(" + std::to_string(end - all[k]->first_slot) + ")";
        if (k == pred_at) same += '>';
      }
      same += ":" + canonical_condition(parts.condition.of(text), formals);
    }

    Successor succ;
    succ.pos = src.locate(parts.predecessor.begin);
    succ.modules = compile_modules(parts.successor.of(text), src.locate, parts.successor.begin, resolve);
    check_brackets(succ.modules, src.locate(parts.successor.begin), "a successor");
    succ.constant = true;
    for (const auto& m : succ.modules) {
      succ.constant_symbols.push_back(m.symbol);
      for (const auto& a : m.args) {
        if (!a.is_constant()) succ.constant = false;
        else succ.constant_params.push_back(a.eval_constant());
      }
    }
    double probability = 1;
    const bool has_prob = parts.probability.present;
    const SourcePos ppos = src.locate(parts.probability.begin);
    if (has_prob) {
      const std::size_t at = parts.probability.begin;
      probability = Expr::compile(parts.probability.of(text), ppos, resolver(nullptr),
                                  [&src, at](std::size_t k) { return src.locate(at + k); })
                        .eval_constant();
      if (!(probability >= 0 && probability <= 1))
        fail_at(ppos, "a probability must lie in [0, 1], got {}", probability);
    }
    succ.cumulative = probability;

    const auto [at, added] = group_of.try_emplace(same, static_cast<int>(t.groups.size()));
    const int gi = at->second;
    if (added) {
      t.groups.push_back(std::move(group));
      explicit_prob.emplace_back();
      prob_pos.emplace_back();
    }
    t.groups[gi].successors.push_back(std::move(succ));
    explicit_prob[gi].push_back(has_prob);
    prob_pos[gi].push_back(has_prob ? ppos : src.locate(parts.successor.end));
  }

  // Stochastic groups: probabilities must be given and sum to 1 (within 1e-9).
  for (std::size_t gi = 0; gi < t.groups.size(); ++gi) {
    RuleGroup& g = t.groups[gi];
    if (g.successors.size() > 1) {
      for (std::size_t k = 0; k < g.successors.size(); ++k)
        if (!explicit_prob[gi][k])
          fail_at(
              prob_pos[gi][k],
              "productions with the same predecessor, contexts and condition ('{}') form a stochastic group; "
              "each needs a probability (': p' after the successor)",
              g.key);
    }
    double sum = 0;
    for (auto& s : g.successors) {
      sum += s.cumulative;
      s.cumulative = sum;
    }
    if (std::fabs(sum - 1) > 1e-9)
      fail_at(prob_pos[gi].front(), "the probabilities of the group '{}' sum to {}, not 1", g.key, sum);
    g.successors.back().cumulative = 1.0;
  }

  t.by_symbol.assign(g_.symbols.size() + 1, {});
  for (std::size_t gi = 0; gi < t.groups.size(); ++gi) {
    const auto& g = t.groups[gi];
    t.by_symbol[g.predecessor.symbol].push_back(static_cast<int>(gi));
    if (!g.left.empty() || !g.right.empty()) t.context_sensitive = true;
  }
  t.mode.assign(t.by_symbol.size(), RewriteMode::copy);
  for (std::size_t s = 0; s < t.by_symbol.size(); ++s) {
    const auto& ids = t.by_symbol[s];
    if (ids.empty()) continue;
    const RuleGroup& g = t.groups[ids[0]];
    const bool simple = ids.size() == 1 && g.left.empty() && g.right.empty() && !g.condition &&
                        g.successors.size() == 1 && g.successors[0].constant;
    t.mode[s] = simple ? RewriteMode::constant : RewriteMode::general;
  }
  (void)what;
  return t;
}

void RuleBuilder::check_turtle_arities(const std::map<Symbol, OrganEntry>& organs) {
  static constexpr std::string_view one_param = "Ff+-&^\\/!";
  static constexpr std::string_view no_param = "|$";
  for (std::size_t s = 0; s < g_.symbols.size(); ++s) {
    const std::string& n = g_.symbols.name(static_cast<Symbol>(s));
    if (n.size() != 1 || organs.count(static_cast<Symbol>(s))) continue;
    const int a = g_.symbols.arity(static_cast<Symbol>(s));
    const SourcePos* at = first_use(static_cast<Symbol>(s));
    if (!at) continue;
    if (one_param.find(n[0]) != std::string_view::npos && a > 1)
      fail_at(*at, "turtle symbol '{}' takes at most one parameter, got {}", n, a);
    if (no_param.find(n[0]) != std::string_view::npos && a > 0)
      fail_at(*at, "turtle symbol '{}' takes no parameter, got {}", n, a);
  }
}

}  // namespace canopy
