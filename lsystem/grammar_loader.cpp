// Reads a grammar file (docs/design.md "Grammar file") into a compiled Grammar.
#include "geometry/layout.hpp"
#include "geometry/prototype.hpp"
#include "lsystem/grammar.hpp"
#include "lsystem/production_syntax.hpp"
#include "lsystem/rule_builder.hpp"
#include "lsystem/yaml_source.hpp"

#include <charconv>
#include <cmath>
#include <set>

namespace canopy {
namespace {

constexpr std::string_view kTopKeys =
    "name seed steps angle step constants axiom productions interpretation ignore organs "
    "compound_leaf tropism stand modules";

bool is_top_key(std::string_view key) {
  for (std::size_t i = 0; i < kTopKeys.size();) {
    std::size_t j = kTopKeys.find(' ', i);
    if (j == std::string_view::npos) j = kTopKeys.size();
    if (kTopKeys.substr(i, j - i) == key) return true;
    i = j + 1;
  }
  return false;
}

bool is_identifier(std::string_view s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  for (char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  return true;
}

class Loader {
 public:
  Loader(const YamlSource& src, const LoadOptions& options) : src_(src), options_(options) {}

  Grammar load(const YAML::Node& root) {
    g_.file = src_.file();
    if (!root.IsMap())
      fail_at(src_.at(root), "a grammar file is a YAML map with keys such as axiom and productions");
    // A file that has none of a grammar's keys is not a grammar with a typo: it may be any file
    // (a path in a positions file, a wrong argument), and its text is not quoted back.
    bool any_known = false;
    for (const auto& kv : root)
      if (kv.first.IsScalar() && is_top_key(kv.first.Scalar())) any_known = true;
    if (!any_known)
      fail_at(src_.at(root),
              "not a grammar file (none of its keys is a grammar's, such as axiom or productions)");
    src_.check_map(root, "the grammar", kTopKeys);
    if (root["name"]) g_.name = src_.string(root["name"], "name");
    if (root["seed"]) g_.seed = src_.seed(root["seed"], "seed");
    if (root["steps"]) g_.steps = static_cast<int>(src_.integer(root["steps"], "steps", 0, kMaxSteps));
    if (root["angle"]) g_.angle = src_.number(root["angle"], "angle");
    if (root["step"]) g_.step = src_.number(root["step"], "step");
    read_constants(root["constants"]);
    if (!root["axiom"]) fail_at({g_.file, 1, 1}, "the grammar has no 'axiom'");

    collect_declared_names(root);
    RuleBuilder builder(g_, ModuleLexer(g_.multi_char_names));
    g_.axiom = builder.module_list(
        src_.string(root["axiom"], "axiom"), [&](std::size_t off) { return src_.at(root["axiom"], off); },
        "the axiom");
    builder.check_brackets(g_.axiom, src_.at(root["axiom"]), "the axiom");
    g_.productions = build_rules(builder, root["productions"], "productions");
    g_.interpretation = build_rules(builder, root["interpretation"], "interpretation");
    read_organs(root["organs"], builder);
    builder.check_turtle_arities(g_.organs);
    note_organs_never_written();
    read_names(root);
    read_tropism(root["tropism"]);
    read_stand(root["stand"]);
    return std::move(g_);
  }

 private:
  /// An organ whose symbol no successor writes grows nothing: a misspelt symbol (organs: {Lf: ...}
  /// beside productions writing L) would give a stand without leaflets and no word of it.
  void note_organs_never_written() {
    std::vector<char> written(g_.symbols.size(), 0);
    for (const SuccessorModule& m : g_.axiom) written[m.symbol] = 1;
    for (const RuleTable* t : {&g_.productions, &g_.interpretation})
      for (const RuleGroup& group : t->groups)
        for (const Successor& s : group.successors)
          for (const SuccessorModule& m : s.modules) written[m.symbol] = 1;
    for (const auto& [sym, organ] : g_.organs)
      if (!written[sym])
        g_.notes.push_back(
            fmt::format("{}:{}:{}: organ '{}' is written by neither the axiom nor any rule, so "
                        "the plants have none (a misspelt symbol?)",
                        organ.pos.file, organ.pos.line, organ.pos.column, g_.symbols.name(sym)));
  }

  void read_constants(const YAML::Node& node) {
    // One value a name: a second --set of it was taken over the first without a word.
    for (std::size_t i = 0; i < options_.overrides.size(); ++i)
      for (std::size_t j = 0; j < i; ++j)
        if (options_.overrides[i].name == options_.overrides[j].name)
          throw std::invalid_argument(fmt::format("--set {}: given twice ({:g} and {:g}); give it once",
                                                  options_.overrides[i].name, options_.overrides[j].value,
                                                  options_.overrides[i].value));
    std::vector<bool> applied(options_.overrides.size(), false);
    if (node && !node.IsNull()) {  // `constants:` with nothing after it: none
      src_.check_map(node, "constants", "");
      for (const auto& kv : node) {
        const std::string name = kv.first.Scalar();
        if (!is_identifier(name))
          fail_at(src_.at(kv.first), "constant name '{}' is not a name (letters, digits, _)", name);
        double value = 0;
        bool overridden = false;
        for (std::size_t i = 0; i < options_.overrides.size(); ++i)
          if (options_.overrides[i].name == name) {
            value = options_.overrides[i].value;
            applied[i] = overridden = true;
          }
        if (!overridden) {
          const std::string text = src_.string(kv.second, fmt::format("constant '{}'", name));
          const Expr e = Expr::compile(
              text, src_.at(kv.second, 0),
              [this](std::string_view n) -> std::optional<NameRef> {
                for (const auto& [cn, cv] : g_.constants)
                  if (cn == n) return NameRef{false, 0, cv};
                return std::nullopt;
              },
              [this, &kv](std::size_t k) { return src_.at(kv.second, k); });
          if (e.uses_rand())
            fail_at(src_.at(kv.second, 0),
                    "constant '{}' may not use rand(); draw per plant in a production instead", name);
          value = e.eval_constant();
        }
        g_.constants.emplace_back(name, value);
      }
    }
    for (std::size_t i = 0; i < options_.overrides.size(); ++i) {
      if (applied[i]) continue;
      std::string known;
      for (const auto& [cn, cv] : g_.constants) known += (known.empty() ? "" : ", ") + cn;
      throw std::invalid_argument(fmt::format("--set {}: {} has no constant '{}' (its constants: {})",
                                              options_.overrides[i].name, src_.file(),
                                              options_.overrides[i].name, known.empty() ? "none" : known));
    }
  }

  void collect_declared_names(const YAML::Node& root) {
    std::set<std::string> names;
    // A name holding white space, a bracket, a parenthesis or a comma would be matched as one
    // module where the file's readers see several ('A B' declared made 'A B' one module and
    // 'A  B' two), or break the brackets and argument lists around it.
    auto add = [&](const std::string& n, const SourcePos& at, const char* what) {
      if (const std::size_t bad = n.find_first_of(" \t\r\n()[],"); bad != std::string::npos) {
        const char c = n[bad];
        fail_at(at, "{} '{}' holds {}, which no module name may: {}", what, n,
                c == ' '                 ? std::string("a space")
                : c == '\t'              ? std::string("a tab")
                : c == '\r' || c == '\n' ? std::string("a line break")
                                         : fmt::format("'{}'", c),
                std::string_view(what) == "the predecessor"
                    ? "a predecessor is one module (its contexts go before '<' and after '>')"
                    : "names are one module each");
      }
      if (n.size() > 1 || (!n.empty() && static_cast<unsigned char>(n[0]) >= 0x80)) names.insert(n);
    };
    if (const auto& o = root["organs"]; o && o.IsMap())
      for (const auto& kv : o) add(kv.first.Scalar(), src_.at(kv.first), "the organ symbol");
    if (const auto& c = root["compound_leaf"]; c)
      add(src_.string(c, "compound_leaf"), src_.at(c), "compound_leaf");
    for (const char* key : {"ignore", "modules"}) {
      if (const auto& l = root[key]; l) {
        src_.check_sequence(l, key);
        for (const auto& item : l)
          add(src_.string(item, key), src_.at(item),
              key == std::string_view("ignore") ? "the ignored name" : "the module name");
      }
    }
    for (const char* key : {"productions", "interpretation"}) {
      const auto& list = root[key];
      if (!list) continue;
      src_.check_sequence(list, key);
      for (const auto& item : list) {
        if (item.IsMap()) continue;  // reported with its place by build_rules
        const std::string text = src_.string(item, "a production");
        const ProductionParts parts = split_production(text, src_.at(item, 0));
        std::string_view pred = parts.predecessor.of(text);
        const std::size_t lead = std::min(pred.find_first_not_of(" \t"), pred.size());
        pred = trim(pred.substr(0, pred.find('(')));
        add(std::string(pred), src_.at(item, parts.predecessor.begin + lead), "the predecessor");
      }
    }
    g_.multi_char_names.assign(names.begin(), names.end());
    std::stable_sort(g_.multi_char_names.begin(), g_.multi_char_names.end(),
                     [](const auto& a, const auto& b) { return a.size() > b.size(); });
  }

  RuleTable build_rules(RuleBuilder& builder, const YAML::Node& list, const char* what) {
    std::vector<RuleBuilder::Source> sources;
    if (list) {
      for (const auto& item : list) {
        RuleBuilder::Source s;
        if (item.IsMap())
          fail_at(src_.at(item),
                  "this production reads as a YAML map because of ': '; quote it: - \"A -> B : ...\"");
        s.text = src_.string(item, "a production");
        s.locate = [this, item](std::size_t off) { return src_.at(item, off); };
        sources.push_back(std::move(s));
      }
    }
    return builder.rule_table(sources, what);
  }

  void read_organs(const YAML::Node& node, RuleBuilder& builder) {
    if (!node || node.IsNull()) return;  // `organs:` with nothing after it: none
    src_.check_map(node, "organs", "");
    for (const auto& kv : node) {
      const std::string name = kv.first.Scalar();
      const YAML::Node& e = kv.second;
      const std::string what = fmt::format("organ '{}'", name);
      src_.check_map(e, what, "prototype kind joint_limit lod");
      OrganEntry organ;
      organ.pos = src_.at(kv.first);
      if (!e["prototype"])
        fail_at(src_.at(kv.first), "{} needs a prototype (cylinder, leaflet, sphere or disk)", what);
      if (!e["kind"])
        fail_at(src_.at(kv.first),
                "{} needs a kind (internode, petiole, rachis, leaflet, peduncle, fruit or flower)", what);
      const std::string proto = src_.string(e["prototype"], "prototype");
      const auto p = parse_prototype(proto);
      if (!p)
        fail_at(src_.at(e["prototype"]),
                "unknown prototype '{}' (expected cylinder, leaflet, sphere or disk)", proto);
      organ.prototype = *p;
      const std::string kind = src_.string(e["kind"], "kind");
      const auto k = parse_organ_kind(kind);
      if (!k)
        fail_at(src_.at(e["kind"]),
                "unknown organ kind '{}' (expected internode, petiole, rachis, leaflet, peduncle, fruit or "
                "flower)",
                kind);
      organ.kind = *k;
      if (e["joint_limit"]) {
        organ.joint_limit_deg = src_.number(e["joint_limit"], "joint_limit");
        if (organ.joint_limit_deg < 0 || organ.joint_limit_deg > 180)
          fail_at(src_.at(e["joint_limit"]), "joint_limit must lie in [0, 180] degrees, got {}",
                  organ.joint_limit_deg);
      }
      if (e["lod"]) organ.lod = static_cast<int>(src_.integer(e["lod"], "lod", 1, kMaxLod));
      const Symbol sym = g_.symbols.intern(name, src_.at(kv.first));
      // A leaflet takes 2 to 5 (its curvature trailing); the name keeps the count it is used with.
      const int least = arity_of(organ.prototype), most = max_arity_of(organ.prototype);
      int want = least;
      if (const SourcePos* used = builder.first_use(sym)) {
        const int n = g_.symbols.arity(sym);
        if (n < least || n > most) {
          if (least == most)
            fail_at(*used, "organ '{}' is a {} and takes {} parameter(s), but is used with {}", name, proto,
                    least, n);
          fail_at(*used, "organ '{}' is a {} and takes {} to {} parameters, but is used with {}", name, proto,
                  least, most, n);
        }
        want = n;
      }
      g_.symbols.set_arity(sym, want);
      g_.organs[sym] = organ;
    }
  }

  void read_names(const YAML::Node& root) {
    if (const auto& c = root["compound_leaf"]) {
      g_.compound_leaf = g_.symbols.intern(src_.string(c, "compound_leaf"), src_.at(c));
      // The symbol opens a compound leaf and emits nothing; as an organ too, its leaflets were
      // left out of every leaf (leaf -1) and of leaf-level detection without a word.
      if (const auto it = g_.organs.find(static_cast<Symbol>(g_.compound_leaf)); it != g_.organs.end())
        fail_at(src_.at(c),
                "compound_leaf '{}' is also an organ ({}:{}:{}): the symbol that begins a compound "
                "leaf emits no organ; give it a name of its own, before the leaf's organs",
                src_.string(c, "compound_leaf"), it->second.pos.file, it->second.pos.line,
                it->second.pos.column);
    }
    std::vector<Symbol> ignored;
    if (const auto& l = root["ignore"])
      for (const auto& item : l) {
        const std::string n = src_.string(item, "ignore");
        if (n == "[" || n == "]") fail_at(src_.at(item), "brackets cannot be ignored");
        ignored.push_back(g_.symbols.intern(n, src_.at(item)));
      }
    if (const auto& l = root["modules"])
      for (const auto& item : l) g_.symbols.intern(src_.string(item, "modules"), src_.at(item));
    g_.ignored.assign(g_.symbols.size(), 0);
    for (Symbol s : ignored) g_.ignored[s] = 1;
    for (RuleTable* t : {&g_.productions, &g_.interpretation}) {
      t->by_symbol.resize(g_.symbols.size());
      t->mode.resize(g_.symbols.size(), RewriteMode::copy);
    }
  }

  void read_tropism(const YAML::Node& node) {
    if (!node) return;
    // `tropism:` with nothing after it is the empty map, as grammar.md says of every such key.
    if (!node.IsNull()) src_.check_map(node, "tropism", "direction strength");
    Tropism t;
    if (const auto& d = node["direction"]) {
      if (!d.IsSequence() || d.size() != 3)
        fail_at(src_.at(d), "tropism direction must be a list of 3 numbers");
      for (int i = 0; i < 3; ++i) {
        t.direction[i] = src_.number(d[i], "a tropism direction component");
        // A direction is normalised in float: components past 1e6 could overflow it.
        if (!(std::abs(t.direction[i]) <= 1e6))
          fail_at(src_.at(d[i]), "a tropism direction component must lie in -1e6..1e6, got {}",
                  t.direction[i]);
      }
      const double n = std::hypot(t.direction[0], t.direction[1], t.direction[2]);
      if (n == 0) fail_at(src_.at(d), "tropism direction must not be zero");
    }
    if (const auto& s = node["strength"]) {
      t.strength = src_.number(s, "tropism strength");
      // The bend per step is strength x |H x T| radians: past 100 it only spins the heading.
      if (!(std::abs(t.strength) <= 100))
        fail_at(src_.at(s), "tropism strength must lie in -100..100, got {}", t.strength);
    }
    g_.tropism = t;
  }

  void read_stand(const YAML::Node& node) {
    if (!node) return;
    // A stand entry is a row layout (these keys) or a positions file, not both.
    static constexpr const char* kRowKeys[] = {"rows",        "per_row", "row_spacing",     "plant_spacing",
                                               "double_rows", "jitter",  "random_rotation", "seed"};
    std::string keys;
    for (const char* k : kRowKeys) keys += std::string(k) + " ";
    if (!node.IsNull()) src_.check_map(node, "stand", keys + "positions");
    StandSpec s;
    auto positive = [&](const char* key) -> std::optional<double> {
      if (!node[key]) return std::nullopt;
      const double v = src_.number(node[key], key);
      if (v < 0) fail_at(src_.at(node[key]), "{} must not be negative, got {}", key, v);
      // Past the reach plants may have, refused here with its place (the layout's own check
      // names the command-line option the value would have come from).
      if (v > kMaxPlantCoordinate)
        fail_at(src_.at(node[key]), "{} is {:g} m: plants may stand at most {:g} m from the origin", key, v,
                kMaxPlantCoordinate);
      return v;
    };
    if (node["rows"]) s.rows = static_cast<int>(src_.integer(node["rows"], "rows", 1, 100000000));
    if (node["per_row"]) s.per_row = static_cast<int>(src_.integer(node["per_row"], "per_row", 1, 100000000));
    s.row_spacing = positive("row_spacing");
    s.plant_spacing = positive("plant_spacing");
    s.double_rows = positive("double_rows");
    s.jitter = positive("jitter");
    if (node["random_rotation"]) s.random_rotation = src_.boolean(node["random_rotation"], "random_rotation");
    if (node["seed"]) s.seed = src_.seed(node["seed"], "seed");
    if (node["positions"]) {
      s.positions = src_.string(node["positions"], "positions");
      for (const char* row : kRowKeys)
        if (node[row])
          fail_at(src_.at(node[row]), "stand: '{}' is a row layout's, and this stand is a positions file's",
                  row);
    }
    for (const char* k : kRowKeys)
      if (node[k]) s.where[k] = src_.at(node[k]).str();
    if (node["positions"]) s.where["positions"] = src_.at(node["positions"]).str();
    g_.stand = s;
  }

  const YamlSource& src_;
  const LoadOptions& options_;
  Grammar g_;
};

}  // namespace

std::optional<double> Grammar::constant(const std::string& n) const {
  for (const auto& [cn, cv] : constants)
    if (cn == n) return cv;
  return std::nullopt;
}

ConstantOverride parse_override(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw std::invalid_argument(fmt::format("--set {}: expected NAME=VALUE", text));
  ConstantOverride o;
  o.name = std::string(trim(std::string_view(text).substr(0, eq)));
  const std::string_view v = unsigned_text(trim(std::string_view(text).substr(eq + 1)));
  const auto r = std::from_chars(v.data(), v.data() + v.size(), o.value);
  if (r.ec == std::errc::result_out_of_range && r.ptr == v.data() + v.size())
    throw std::invalid_argument(
        fmt::format("--set {}: '{}' is out of a double's range (about 1e-308 to 1e308 in size)", text, v));
  if (r.ec != std::errc() || r.ptr != v.data() + v.size() || !std::isfinite(o.value))
    throw std::invalid_argument(fmt::format(
        "--set {}: '{}' is not a finite number (a value, not an expression: 6, not 2*3)", text, v));
  return o;
}

Grammar parse_grammar(const std::string& text, const std::string& file, const LoadOptions& options) {
  const YAML::Node root = parse_yaml_document(text, file);
  const YamlSource src(file, text);
  try {
    return Loader(src, options).load(root);
  } catch (const YAML::Exception& e) {
    throw GrammarError({file, e.mark.line + 1, e.mark.column + 1}, "unexpected YAML structure: " + e.msg);
  }
}

Grammar load_grammar(const std::string& path, const LoadOptions& options) {
  return parse_grammar(read_grammar_file(path), path, options);
}

}  // namespace canopy
