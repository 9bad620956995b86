#include "lsystem/turtle.hpp"

#include "geometry/leaflet_shape.hpp"
#include "lsystem/module_format.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace canopy {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

struct State {
  TurtleFrame f;
  int last_organ = -1;
  int leaf_slot = -1;  // the compound leaf this state is in (index into the slots), -1 outside
};

/// Rotates a and b (two frame vectors) by angle in their plane: a' = a cos + b sin, b' = b cos - a sin.
void rotate_pair(Vec3d& a, Vec3d& b, double angle_deg) {
  const double c = std::cos(angle_deg * kDeg), s = std::sin(angle_deg * kDeg);
  const Vec3d na = a * c + b * s;
  const Vec3d nb = b * c - a * s;
  a = na;
  b = nb;
}

/// Rodrigues rotation of v about unit axis k by angle (radians).
Vec3d rotate(Vec3d v, Vec3d k, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return v * c + cross(k, v) * s + k * (dot(k, v) * (1 - c));
}

/// ABOP §2.2: bend H towards T by alpha = e |H x T| about H x T, carrying the whole frame.
void apply_tropism(TurtleFrame& f, const Tropism& t) {
  const Vec3d dir = normalized({t.direction[0], t.direction[1], t.direction[2]});
  const Vec3d axis = cross(f.heading, dir);
  const double n = length(axis);
  if (n < 1e-12 || t.strength == 0) return;
  const double alpha = t.strength * n;
  const Vec3d k = axis * (1 / n);
  f.heading = normalized(rotate(f.heading, k, alpha));
  f.left = normalized(rotate(f.left, k, alpha));
  f.up = cross(f.heading, f.left);
}

}  // namespace

Affine3f organ_transform(PrototypeKind prototype, const float* p, const TurtleFrame& f) {
  Affine3f m;
  m.t = to_float(f.position);
  double sx = 1, sy = 1, sz = 1;
  switch (prototype) {
    case PrototypeKind::cylinder: sx = p[0], sy = sz = p[1]; break;
    case PrototypeKind::leaflet: sx = p[0], sy = sz = p[1]; break;
    case PrototypeKind::sphere:
    case PrototypeKind::disk: sx = sy = sz = p[0]; break;
  }
  m.c0 = to_float(f.heading * sx);
  m.c1 = to_float(f.left * sy);
  m.c2 = to_float(f.up * sz);
  return m;
}

TurtleResult run_turtle(const Grammar& g, const ModuleString& s, const TurtleConfig& config) {
  TurtleResult out;
  std::vector<State> stack;
  State st;
  // A compound leaf gets its id when its first organ appears, so leaves with no organs (a bud
  // not yet unfolded) take no id; ids stay in string order.
  std::vector<int> leaf_ids;
  std::vector<const OrganEntry*> organ_of(g.symbols.size(), nullptr);
  for (const auto& [sym, entry] : g.organs) organ_of[sym] = &entry;
  const auto fail = [&](std::size_t i, std::size_t p, const std::string& what, int parameter = -1) {
    ModuleString one;
    one.symbols.push_back(s.symbols[i]);
    const int ar = std::max(0, g.symbols.arity(s.symbols[i]));
    one.params.append(s.params.data() + p, static_cast<std::size_t>(ar));
    throw TurtleError(g.file,
                      fmt::format("{}, module {} '{}': {}", config.where, i, format_modules(g, one), what), i,
                      parameter);
  };
  // An organ farther than kMaxOrganExtent from the plant's origin along an axis.
  const auto too_far = [](const Vec3d& v) {
    return !(std::fabs(v.x) <= kMaxOrganExtent && std::fabs(v.y) <= kMaxOrganExtent &&
             std::fabs(v.z) <= kMaxOrganExtent);
  };
  std::size_t p = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const Symbol x = s.symbols[i];
    const int ar = std::max(0, g.symbols.arity(x));
    const double* a = s.params.data() + p;
    const auto arg = [&](double dflt) { return ar > 0 ? a[0] : dflt; };
    for (int k = 0; k < ar; ++k)
      if (!std::isfinite(a[k])) fail(i, p, fmt::format("parameter {} is not finite", k + 1), k);
    if (const OrganEntry* organ = organ_of[x]) {
      OrganInstance o;
      o.kind = organ->kind;
      o.prototype = organ->prototype;
      for (int k = 0; k < ar && k < 2; ++k) {
        if (a[k] < 0)
          fail(i, p, fmt::format("{} parameter {} must not be negative", name_of(o.prototype), k + 1), k);
        if (a[k] > kMaxOrganExtent)
          fail(i, p,
               fmt::format("{} parameter {} is {} m, more than the {} m an organ may measure",
                           name_of(o.prototype), k + 1, a[k], kMaxOrganExtent),
               k);
        o.params[k] = static_cast<float>(a[k]);
      }
      if (o.prototype == PrototypeKind::leaflet && ar > 2) {
        // bend, cup, fold (degrees), rounded to their steps; those left out are 0.
        std::string why;
        const auto code = leaflet_shape_code({a[2], ar > 3 ? a[3] : 0.0, ar > 4 ? a[4] : 0.0}, &why);
        if (!code) fail(i, p, why);
        o.shape = *code;
      }
      if (too_far(st.f.position))
        fail(i, p, fmt::format("the organ lies farther than {} m from its plant's origin", kMaxOrganExtent));
      o.parent = st.last_organ;
      if (st.leaf_slot >= 0) {
        int& id = leaf_ids[static_cast<std::size_t>(st.leaf_slot)];
        if (id < 0) id = out.leaf_count++;
        o.leaf = id;
      }
      o.lod = organ->lod.value_or(config.lod);
      o.joint_limit_deg = static_cast<float>(organ->joint_limit_deg);
      o.transform = organ_transform(o.prototype, o.params, st.f);
      o.module = static_cast<std::uint32_t>(i);
      st.last_organ = static_cast<int>(out.organs.size());
      out.organs.push_back(o);
      if (o.prototype == PrototypeKind::cylinder) {
        // A cylinder advances the turtle as F does, within the same bound (its far end is the
        // next organ's base).
        st.f.position = st.f.position + st.f.heading * static_cast<double>(o.params[0]);
        if (too_far(st.f.position))
          fail(i, p,
               fmt::format("the cylinder takes the turtle farther than {} m from the plant's origin",
                           kMaxOrganExtent),
               0);
        if (g.tropism) apply_tropism(st.f, *g.tropism);
      }
    } else if (static_cast<int>(x) == g.compound_leaf) {
      st.leaf_slot = static_cast<int>(leaf_ids.size());
      leaf_ids.push_back(-1);
    } else if (x == g.symbols.open_bracket()) {
      stack.push_back(st);
    } else if (x == g.symbols.close_bracket()) {
      if (stack.empty()) fail(i, p, "']' closes no '['");
      st = stack.back();
      stack.pop_back();
    } else {
      const std::string& n = g.symbols.name(x);
      if (n.size() == 1) {
        switch (n[0]) {
          case 'F':
          case 'f': {
            const double l = arg(g.step);
            if (l < 0) fail(i, p, "a step length must not be negative", 0);
            st.f.position = st.f.position + st.f.heading * l;
            if (too_far(st.f.position))
              fail(i, p,
                   fmt::format("the step takes the turtle farther than {} m from the plant's origin",
                               kMaxOrganExtent),
                   0);
            if (n[0] == 'F' && g.tropism) apply_tropism(st.f, *g.tropism);
            break;
          }
          case '+': rotate_pair(st.f.heading, st.f.left, -arg(g.angle)); break;
          case '-': rotate_pair(st.f.heading, st.f.left, arg(g.angle)); break;
          case '&': rotate_pair(st.f.heading, st.f.up, arg(g.angle)); break;
          case '^': rotate_pair(st.f.heading, st.f.up, -arg(g.angle)); break;
          case '\\': rotate_pair(st.f.left, st.f.up, arg(g.angle)); break;
          case '/': rotate_pair(st.f.left, st.f.up, -arg(g.angle)); break;
          case '|': rotate_pair(st.f.heading, st.f.left, 180); break;
          case '$': {
            const Vec3d v{0, 0, 1};
            const Vec3d l = cross(v, st.f.heading);
            if (length(l) > 1e-12) {
              st.f.left = normalized(l);
              st.f.up = cross(st.f.heading, st.f.left);
            }
            break;
          }
          default: break;  // '!' (width) and other modules draw nothing
        }
      }
    }
    p += static_cast<std::size_t>(ar);
  }
  return out;
}

}  // namespace canopy
