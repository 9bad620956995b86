// An end-to-end check that does not use canopy's predicates: CGAL's exact predicates on the
// triangles of an exported stand.obj (or stand.glb with --glb), against the exact rows of
// contacts.csv. Organ pairs that disagree are allowed only where the organs come within 1 um of
// each other (docs/design.md: closer than that either answer is allowed; the OBJ itself is rounded to
// 0.1 um). With --glb the triangles are the file's own, decoded: on a compact glb that checks the
// quantized positions themselves.
// Every organ kind is checked unless --collide narrows them (to the kinds a run was narrowed to).
// Usage: check_cgal DIR [--collide KINDS] [--contacts FILE] [--glb] [--strict]   (FILE in DIR,
// default contacts.csv; contacts_after.csv checks a resolved stand: only what resolution reported
// left may meet; --strict: every pair that meets must be listed, however close, as a mesh whose
// positions were rounded must not meet where the stand it came from did not)
#include "collision/contacts.hpp"
#include "collision/mbvt.hpp"
#include "geometry/export.hpp"
#include "tools/bench_usage.hpp"
#include "tools/organ_triangles.hpp"

#include <CGAL/intersections.h>
#include <CGAL/squared_distance_3.h>

#include <fmt/format.h>

#include <cstring>
#include <fstream>
#include <set>

using K = canopy::check::Kernel;
using Point = K::Point_3;
using Triangle = K::Triangle_3;
using Segment = K::Segment_3;
using canopy::check::OrganGeometry;
using namespace canopy;

namespace {

/// A triangle that may be degenerate, as CGAL objects: a triangle, up to three segments, or a point.
bool meet(const Point& a0, const Point& a1, const Point& a2, const Point& b0, const Point& b1,
          const Point& b2) {
  const Triangle ta(a0, a1, a2), tb(b0, b1, b2);
  const bool da = ta.is_degenerate(), db = tb.is_degenerate();
  if (!da && !db) return CGAL::do_intersect(ta, tb);
  auto pieces = [](const Point& p, const Point& q, const Point& r) {
    std::vector<Segment> s;
    for (auto [x, y] : {std::pair{p, q}, std::pair{q, r}, std::pair{r, p}})
      if (x != y) s.emplace_back(x, y);
    return s;
  };
  if (da && !db) {
    const auto s = pieces(a0, a1, a2);
    if (s.empty()) return tb.has_on(a0);
    for (const auto& x : s)
      if (CGAL::do_intersect(x, tb)) return true;
    return false;
  }
  if (!da && db) return meet(b0, b1, b2, a0, a1, a2);
  const auto sa = pieces(a0, a1, a2), sb = pieces(b0, b1, b2);
  if (sa.empty() && sb.empty()) return a0 == b0;
  if (sa.empty()) {
    for (const auto& y : sb)
      if (y.has_on(a0)) return true;
    return false;
  }
  if (sb.empty()) return meet(b0, b1, b2, a0, a1, a2);
  for (const auto& x : sa)
    for (const auto& y : sb)
      if (CGAL::do_intersect(x, y)) return true;
  return false;
}

bool inside_convex(const Point& p, const OrganGeometry& solid) {
  bool inner = false;
  for (const auto& f : solid.f) {
    const auto o = CGAL::orientation(solid.v[f[0]], solid.v[f[1]], solid.v[f[2]], p);
    if (o == CGAL::POSITIVE) return false;
    inner |= o == CGAL::NEGATIVE;
  }
  return inner;
}

double min_distance2(const OrganGeometry& a, const OrganGeometry& b) {
  double best = 1e300;
  for (const auto& fa : a.f)
    for (const auto& fb : b.f) {
      const Triangle ta(a.v[fa[0]], a.v[fa[1]], a.v[fa[2]]), tb(b.v[fb[0]], b.v[fb[1]], b.v[fb[2]]);
      if (ta.is_degenerate() || tb.is_degenerate()) {
        for (int i = 0; i < 3; ++i)
          best = std::min(best, CGAL::to_double(CGAL::squared_distance(a.v[fa[i]], b.v[fb[0]])));
        continue;
      }
      best = std::min(best, CGAL::to_double(CGAL::squared_distance(ta, tb)));
    }
  return best;
}

}  // namespace

int run_check(int argc, char** argv);

int main(int argc, char** argv) {
  try {
    return run_check(argc, argv);
  } catch (const std::exception& e) {
    fmt::print(stderr, "check_cgal: error: {}\n", e.what());
    return 1;
  }
}

int run_check(int argc, char** argv) {
  const std::string usage =
      "usage: check_cgal DIR [--collide KINDS (default all)] [--contacts FILE] [--glb] [--strict]\n";
  std::string dir;
  KindMask collide = parse_collide_kinds("all");  // every organ in the file, fruit and flowers included
  std::string contacts_file = "contacts.csv";
  bool glb = false, strict = false;
  for (int i = 1; i < argc; ++i)
    if (!std::strcmp(argv[i], "--glb")) glb = true;
    else if (!std::strcmp(argv[i], "--strict")) strict = true;
    else if (i + 1 < argc && !std::strcmp(argv[i], "--collide")) collide = parse_collide_kinds(argv[++i]);
    else if (i + 1 < argc && !std::strcmp(argv[i], "--contacts")) contacts_file = argv[++i];
    else if (argv[i][0] != '-' && dir.empty()) dir = argv[i];
    else return help_or_refuse("check_cgal", argv[i], usage);
  if (dir.empty()) {
    std::fputs(usage.c_str(), stderr);
    return 2;
  }
  const Stand s = read_stand(dir);
  std::vector<OrganGeometry> organs(s.organ_count());
  if (glb) check::read_glb_organs(dir + "/stand.glb", organs);
  else check::read_obj_organs(dir + "/stand.obj", organs);
  std::set<std::pair<int, int>> listed;
  {
    std::ifstream in(dir + "/" + contacts_file);
    std::string line;
    std::getline(in, line);
    while (std::getline(in, line)) {
      int a, b, pa, pb;
      char level[16];
      if (std::sscanf(line.c_str(), "%d,%d,%d,%d,%15s", &a, &b, &pa, &pb, level) == 5 &&
          std::string(level) == "exact")
        listed.insert({a, b});
    }
  }
  std::size_t tested = 0, found = 0, near = 0, bad = 0;
  for (std::size_t a = 0; a < organs.size(); ++a) {
    if (!collide[static_cast<std::size_t>(s.organs[a].kind)]) continue;
    for (std::size_t b = a + 1; b < organs.size(); ++b) {
      if (!collide[static_cast<std::size_t>(s.organs[b].kind)]) continue;
      if (adjacent(s.organs[a], static_cast<std::int32_t>(a), s.organs[b], static_cast<std::int32_t>(b)))
        continue;
      const OrganGeometry &ga = organs[a], &gb = organs[b];
      bool apart = false;
      for (int k = 0; k < 3; ++k) apart |= ga.lo[k] > gb.hi[k] + 1e-6 || gb.lo[k] > ga.hi[k] + 1e-6;
      const bool in_list = listed.count({static_cast<int>(a), static_cast<int>(b)}) > 0;
      if (apart && !in_list) continue;
      ++tested;
      bool hit = false;
      for (std::size_t i = 0; i < ga.f.size() && !hit; ++i)
        for (std::size_t j = 0; j < gb.f.size() && !hit; ++j)
          hit = meet(ga.v[ga.f[i][0]], ga.v[ga.f[i][1]], ga.v[ga.f[i][2]], gb.v[gb.f[j][0]], gb.v[gb.f[j][1]],
                     gb.v[gb.f[j][2]]);
      const auto solid = [](PrototypeKind k) {
        return k == PrototypeKind::cylinder || k == PrototypeKind::sphere;
      };
      if (!hit && solid(s.organs[b].prototype)) hit = inside_convex(ga.v[0], gb);
      if (!hit && solid(s.organs[a].prototype)) hit = inside_convex(gb.v[0], ga);
      found += hit;
      if (hit != in_list) {
        const double d = std::sqrt(min_distance2(ga, gb));
        if (d <= 1e-6 && !(strict && hit)) ++near;
        else {
          ++bad;
          if (bad <= 10)
            fmt::print("disagree: organs {} {}: CGAL {}, contacts.csv {}, distance {:.3g} m\n", a, b, hit,
                       in_list, d);
        }
      }
    }
  }
  fmt::print(
      "CGAL check of {} ({}) against {}: {} organ pairs tested, {} meet by CGAL, {} listed, {} disagree "
      "within 1 um, {} "
      "disagree\n",
      dir, glb ? "stand.glb" : "stand.obj", contacts_file, tested, found, listed.size(), near, bad);
  return bad == 0 ? 0 : 1;
}
