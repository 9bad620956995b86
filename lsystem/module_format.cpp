#include "lsystem/module_format.hpp"

#include <nlohmann/json.hpp>

#include <charconv>
#include <map>
#include <stdexcept>
#include <unordered_map>

namespace canopy {
namespace {

/// Whether `a` (written without parameters) followed by `b` could lex as a longer declared name.
bool needs_space(const Grammar& g, Symbol a, Symbol b) {
  const std::string& an = g.symbols.name(a);
  const std::string& bn = g.symbols.name(b);
  const bool b_bare = g.symbols.arity(b) <= 0;
  for (const std::string& n : g.multi_char_names) {
    if (n.size() <= an.size() || n.compare(0, an.size(), an) != 0) continue;
    const std::string_view rest = std::string_view(n).substr(an.size());
    if (std::string_view(bn).substr(0, rest.size()) == rest) return true;
    if (b_bare && rest.substr(0, bn.size()) == bn) return true;  // may go on into what follows b
  }
  return false;
}

class Writer {
 public:
  explicit Writer(std::FILE* f) : f_(f) {}
  ~Writer() { flush(); }
  void put(std::string_view s) {
    if (buf_.size() + s.size() > kCap) flush();
    buf_.append(s);
  }
  void put(char c) {
    if (buf_.size() + 1 > kCap) flush();
    buf_.push_back(c);
  }
  void flush() {
    if (f_ && !buf_.empty()) std::fwrite(buf_.data(), 1, buf_.size(), f_);
    if (f_) buf_.clear();
  }
  std::string take() { return std::move(buf_); }

 private:
  static constexpr std::size_t kCap = std::size_t(1) << 20;
  std::FILE* f_;
  std::string buf_;
};

void emit(Writer& w, const Grammar& g, const ModuleString& s) {
  std::unordered_map<std::uint32_t, bool> space;  // per (previous, next) pair, on first use
  std::size_t p = 0;
  char num[64];
  for (std::size_t i = 0; i < s.size(); ++i) {
    const Symbol x = s.symbols[i];
    const int ar = std::max(0, g.symbols.arity(x));
    if (i > 0 && std::max(0, g.symbols.arity(s.symbols[i - 1])) == 0 && !g.multi_char_names.empty()) {
      const std::uint32_t key = (static_cast<std::uint32_t>(s.symbols[i - 1]) << 16) | x;
      auto it = space.find(key);
      if (it == space.end()) it = space.emplace(key, needs_space(g, s.symbols[i - 1], x)).first;
      if (it->second) w.put(' ');
    }
    w.put(g.symbols.name(x));
    if (ar) {
      w.put('(');
      for (int k = 0; k < ar; ++k) {
        if (k) w.put(',');
        const auto r = std::to_chars(num, num + sizeof num, s.params[p + static_cast<std::size_t>(k)]);
        if (r.ec != std::errc())
          throw std::range_error(
              "a module parameter does not fit its number field");  // never: 24 characters at most
        w.put(std::string_view(num, static_cast<std::size_t>(r.ptr - num)));
      }
      w.put(')');
    }
    p += static_cast<std::size_t>(ar);
  }
}

}  // namespace

std::string format_number(double v) {
  char num[64];
  const auto r = std::to_chars(num, num + sizeof num, v);
  if (r.ec != std::errc())
    throw std::range_error("a number does not fit its field");  // never: 24 characters at most
  return std::string(num, r.ptr);
}

void write_modules(std::FILE* out, const Grammar& g, const ModuleString& s) {
  Writer w(out);
  emit(w, g, s);
}

std::string format_modules(const Grammar& g, const ModuleString& s) {
  Writer w(nullptr);
  emit(w, g, s);
  return w.take();
}

std::vector<std::size_t> count_modules(const Grammar& g, const ModuleString& s) {
  std::vector<std::size_t> counts(g.symbols.size(), 0);
  for (Symbol x : s.symbols) ++counts[x];
  return counts;
}

std::string stats_json(const Grammar& g, const ModuleString& s) {
  const auto counts = count_modules(g, s);
  std::map<std::string, std::size_t> by_name;
  for (std::size_t k = 0; k < counts.size(); ++k)
    if (counts[k]) by_name[g.symbols.name(static_cast<Symbol>(k))] = counts[k];
  std::string out = fmt::format("{{\"modules\": {}, \"counts\": {{", s.size());
  bool first = true;
  for (const auto& [name, n] : by_name) {
    out +=
        fmt::format("{}{}: {}", first ? "" : ", ",
                    nlohmann::json(name).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace), n);
    first = false;
  }
  return out + "}}";
}

}  // namespace canopy
