#include "lsystem/derive.hpp"

#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace canopy {
namespace {

/// The cap passed: named at the production whose successor made the string pass it (where none
/// applied yet, the axiom). `step`: the derivation step, 0 for the axiom, -1 the interpretation.
/// Whether `s` is past the module cap: its modules, or its parameters past kParamsPerModule per
/// module of the cap (a module of many parameters weighs as much as many modules: each is 8
/// bytes, twice over while a step writes the next string).
std::size_t params_cap(std::size_t cap) {
  return cap > SIZE_MAX / kParamsPerModule ? SIZE_MAX
                                           : kParamsPerModule * cap;  // Stand.grow takes any size_t
}

bool over_cap(const ModuleString& s, std::size_t cap) {
  return s.symbols.size() > cap || s.params.size() > params_cap(cap);
}

[[noreturn]] void cap_exceeded(const Grammar& g, const ModuleString& s, std::size_t cap, int step,
                               const SourcePos* where) {
  SourcePos at = where ? *where : g.axiom.empty() ? SourcePos{g.file, 0, 0} : g.axiom.front().pos;
  if (at.file.empty()) at.file = g.file;
  const std::string what =
      s.symbols.size() > cap
          ? fmt::format("the module cap of {} modules", cap)
          : fmt::format("the {} parameters the module cap of {} modules allows ({} per module)",
                        params_cap(cap), cap, kParamsPerModule);
  if (step == 0)
    throw ModuleCapError(fmt::format("{}: the axiom has more than {} (raise --max-modules)", at.str(), what));
  const std::string when = step > 0 ? fmt::format(" at step {}, as this production applied", step)
                                    : std::string(" in the interpretation, as this production applied");
  throw ModuleCapError(fmt::format(
      "{}: the derived string exceeds {}{} (the grammar grows too fast for this many steps; lower --steps or "
      "raise --max-modules)",
      at.str(), what, when));
}

/// Copies a module's `n` parameters, starting at params[offset], into the production's frame.
inline void bind(double* frame, const double* params, std::size_t offset, int n) {
  if (n > 0) std::memcpy(frame, params + offset, sizeof(double) * static_cast<std::size_t>(n));
}

ModuleString evaluate_axiom(const Grammar& g, Rng& rng) {
  ModuleString s;
  for (const auto& m : g.axiom) {
    s.symbols.push_back(m.symbol);
    for (const auto& a : m.args) s.params.push_back(a.eval(nullptr, rng));
  }
  return s;
}

}  // namespace

void ContextIndex::build(const Grammar& g, const ModuleString& s) {
  const std::size_t n = s.size();
  if (n >= static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    throw ModuleCapError("string too long for context matching (2^31 modules)");
  left.resize(n);
  right.resize(n);
  param_offset.resize(n + 1);
  const Symbol open = g.symbols.open_bracket(), close = g.symbols.close_bracket();
  const auto ignored = [&](Symbol x) { return x < g.ignored.size() && g.ignored[x]; };
  PodBuffer<std::int32_t> stack;
  std::uint64_t off = 0;
  std::int32_t last = -1;
  for (std::size_t i = 0; i < n; ++i) {
    const Symbol x = s.symbols[i];
    param_offset[i] = static_cast<std::uint32_t>(off);
    off += static_cast<std::uint64_t>(g.symbols.arity(x) < 0 ? 0 : g.symbols.arity(x));
    if (off > std::numeric_limits<std::uint32_t>::max())
      throw ModuleCapError("too many parameters for context matching");
    left[i] = last;
    if (x == open) stack.push_back(last);
    else if (x == close) {
      if (stack.empty()) throw ModuleCapError("unbalanced ']' in the derived string");
      last = stack[stack.size() - 1];
      stack.resize(stack.size() - 1);
    } else if (!ignored(x)) last = static_cast<std::int32_t>(i);
  }
  param_offset[n] = static_cast<std::uint32_t>(off);
  stack.clear();
  std::int32_t next = -1;
  for (std::size_t k = n; k-- > 0;) {
    const Symbol x = s.symbols[k];
    right[k] = next;
    if (x == close) {  // modules inside this branch end at its ']': no right context past it
      stack.push_back(next);
      next = -1;
    } else if (x == open) {
      if (stack.empty()) next = -1;
      else {
        next = stack[stack.size() - 1];
        stack.resize(stack.size() - 1);
      }
    } else if (!ignored(x)) next = static_cast<std::int32_t>(k);
  }
}

namespace {

/// Where each module of a string was written: the axiom's or a successor's module.
using Origins = PodBuffer<const SuccessorModule*>;

/// One rewriting step; with Track, also the origin of every module written (`in_origin` for
/// `in`, `out_origin` for `out`): the slow path that locates an error found after derivation.
/// Both forms draw the same numbers, so the tracked run derives the same string.
template <bool Track>
void rewrite_step(const Grammar& g, const RuleTable& table, const ModuleString& in, ModuleString& out,
                  Rng& rng, std::size_t max_modules, int step, const Origins* in_origin, Origins* out_origin) {
  const SourcePos* applied = nullptr;  // the production applied last: where the cap is named
  if constexpr (Track) out_origin->clear();
  out.symbols.clear();
  out.params.clear();
  out.symbols.reserve(in.size() + in.size() / 2 + 16);
  out.params.reserve(in.params.size() + in.params.size() / 2 + 16);
  ContextIndex ctx;
  if (table.context_sensitive) ctx.build(g, in);

  const std::size_t nsym = table.mode.size();
  std::vector<int> arity(g.symbols.size());
  for (std::size_t s = 0; s < arity.size(); ++s)
    arity[s] = std::max(0, g.symbols.arity(static_cast<Symbol>(s)));

  const Symbol* sym = in.symbols.data();
  const double* par = in.params.data();
  const std::size_t n = in.size();
  std::size_t p = 0;
  double frame[kMaxFrame];
  for (std::size_t i = 0; i < n; ++i) {
    const Symbol x = sym[i];
    const int ar = arity[x];
    const RewriteMode mode = x < nsym ? table.mode[x] : RewriteMode::copy;
    if (mode == RewriteMode::copy) {
      // A run of modules that stay as they are: copied in one piece.
      std::size_t j = i + 1, q = p + static_cast<std::size_t>(ar);
      while (j < n && (sym[j] >= nsym || table.mode[sym[j]] == RewriteMode::copy))
        q += static_cast<std::size_t>(arity[sym[j++]]);
      out.symbols.append(sym + i, j - i);
      out.params.append(par + p, q - p);
      if constexpr (Track) out_origin->append(in_origin->data() + i, j - i);
      i = j - 1;
      p = q;
      if (over_cap(out, max_modules)) cap_exceeded(g, out, max_modules, step, applied);
      continue;
    } else if (mode == RewriteMode::constant) {
      const Successor& sc = table.groups[table.by_symbol[x][0]].successors[0];
      applied = &sc.pos;
      out.symbols.append(sc.constant_symbols.data(), sc.constant_symbols.size());
      out.params.append(sc.constant_params.data(), sc.constant_params.size());
      if constexpr (Track)
        for (const SuccessorModule& m : sc.modules) out_origin->push_back(&m);
    } else {
      bool matched = false;
      for (int gi : table.by_symbol[x]) {
        const RuleGroup& rg = table.groups[static_cast<std::size_t>(gi)];
        std::int32_t j = static_cast<std::int32_t>(i);
        bool ok = true;
        for (std::size_t k = rg.left.size(); ok && k-- > 0;) {
          j = ctx.left[static_cast<std::size_t>(j)];
          if (j < 0 || sym[j] != rg.left[k].symbol) ok = false;
          else
            bind(frame + rg.left[k].first_slot, par, ctx.param_offset[static_cast<std::size_t>(j)],
                 arity[sym[j]]);
        }
        j = static_cast<std::int32_t>(i);
        for (std::size_t k = 0; ok && k < rg.right.size(); ++k) {
          j = ctx.right[static_cast<std::size_t>(j)];
          if (j < 0 || sym[j] != rg.right[k].symbol) ok = false;
          else
            bind(frame + rg.right[k].first_slot, par, ctx.param_offset[static_cast<std::size_t>(j)],
                 arity[sym[j]]);
        }
        if (!ok) continue;
        bind(frame + rg.predecessor.first_slot, par, p, ar);
        if (rg.condition && rg.condition->eval(frame, rng) == 0) continue;
        const Successor* sc = &rg.successors[0];
        if (rg.successors.size() > 1) {
          const double u = rng.uniform();
          for (const auto& cand : rg.successors) {
            sc = &cand;
            if (u < cand.cumulative) break;
          }
        }
        if constexpr (Track)
          for (const SuccessorModule& m : sc->modules) out_origin->push_back(&m);
        if (sc->constant) {
          out.symbols.append(sc->constant_symbols.data(), sc->constant_symbols.size());
          out.params.append(sc->constant_params.data(), sc->constant_params.size());
        } else {
          for (const SuccessorModule& m : sc->modules) {
            out.symbols.push_back(m.symbol);
            for (const Expr& e : m.args) out.params.push_back(e.eval(frame, rng));
          }
        }
        matched = true;
        applied = &sc->pos;
        break;
      }
      if (!matched) {
        out.symbols.push_back(x);
        if (ar) out.params.append(par + p, static_cast<std::size_t>(ar));
        if constexpr (Track) out_origin->push_back((*in_origin)[i]);
      }
    }
    p += static_cast<std::size_t>(ar);
    if (over_cap(out, max_modules)) cap_exceeded(g, out, max_modules, step, applied);
  }
}

}  // namespace

void rewrite(const Grammar& g, const RuleTable& table, const ModuleString& in, ModuleString& out, Rng& rng,
             std::size_t max_modules, int step) {
  rewrite_step<false>(g, table, in, out, rng, max_modules, step, nullptr, nullptr);
}

ModuleString derive(const Grammar& g, const DeriveRequest& req) {
  const int steps = req.steps.value_or(g.steps);
  if (steps < 0 || steps > kMaxSteps)
    throw std::invalid_argument(
        fmt::format("the derivation steps must lie in 0..{} (got {})", kMaxSteps, steps));
  Rng rng(req.seed.value_or(g.seed));
  ModuleString cur = evaluate_axiom(g, rng);
  if (over_cap(cur, req.max_modules)) cap_exceeded(g, cur, req.max_modules, 0, nullptr);
  if (g.productions.empty()) return cur;
  ModuleString next;
  for (int step = 1; step <= steps; ++step) {
    rewrite(g, g.productions, cur, next, rng, req.max_modules, step);
    std::swap(cur, next);
  }
  return cur;
}

namespace {

Rng interpretation_stream(std::uint64_t seed) {
  std::uint64_t s = seed;
  return Rng(Rng::splitmix64(s) ^ 0x696e746572707265ULL);  // "interpre": a stream apart from derivation's
}

}  // namespace

ModuleString interpret(const Grammar& g, const ModuleString& derived, std::uint64_t seed,
                       std::size_t max_modules) {
  if (g.interpretation.empty()) return derived;
  Rng rng = interpretation_stream(seed);
  ModuleString out;
  rewrite(g, g.interpretation, derived, out, rng, max_modules, -1);
  return out;
}

std::optional<SourcePos> module_source(const Grammar& g, const DeriveRequest& req, bool interpreted,
                                       std::size_t module, int parameter) {
  const int steps = req.steps.value_or(g.steps);
  const std::uint64_t seed = req.seed.value_or(g.seed);
  Rng rng(seed);
  ModuleString cur = evaluate_axiom(g, rng);
  Origins origin, next_origin;
  for (const SuccessorModule& m : g.axiom) origin.push_back(&m);
  ModuleString next;
  if (!g.productions.empty())
    for (int step = 1; step <= steps; ++step) {
      rewrite_step<true>(g, g.productions, cur, next, rng, req.max_modules, step, &origin, &next_origin);
      std::swap(cur, next);
      std::swap(origin, next_origin);
    }
  if (interpreted && !g.interpretation.empty()) {
    Rng irng = interpretation_stream(seed);
    rewrite_step<true>(g, g.interpretation, cur, next, irng, req.max_modules, -1, &origin, &next_origin);
    std::swap(origin, next_origin);
  }
  if (module >= origin.size() || !origin[module]) return std::nullopt;
  const SuccessorModule& m = *origin[module];
  if (parameter >= 0 && static_cast<std::size_t>(parameter) < m.args.size() &&
      m.args[static_cast<std::size_t>(parameter)].pos().line > 0)
    return m.args[static_cast<std::size_t>(parameter)].pos();
  return m.pos;
}

}  // namespace canopy
