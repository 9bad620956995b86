#pragma once
/// The exact level for one organ pair on the host: the organs' triangles made on the fly from
/// prototype x transform (the higher organ moved into the lower organ's plant frame by the
/// origin difference), a triangle-box filter, then the shared closed triangle test; capped
/// cylinders and spheres are solids, so an organ wholly inside one counts too.
#include "geometry/prototype.hpp"
#include "geometry/stand.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace canopy {

/// A quick, conservative rejection before the exact triangle test, on the vertices that test
/// receives: a separating-axis test in float along a triangle's (unnormalised) normal n. The
/// triangle's own projections n . p_k span [lo, hi] (a point when n is exact, an interval when
/// a sliver's normal is not), the other's must lie wholly beyond it by more than `margin` x |n|.
/// Any axis separating the two by that much keeps them more than `margin` apart, and the float
/// rounding (about 1e-7 m at plant scale) is far below the margin's slack over the clearance, so
/// the exact test would have rejected them too.
struct TrianglePlane {
  Vec3f n;
  float lo = 0, hi = 0, lim = 0;
  static TrianglePlane of(Vec3f p0, Vec3f p1, Vec3f p2, float margin) {
    TrianglePlane t;
    t.n = cross(p1 - p0, p2 - p0);
    const float d0 = dot(t.n, p0), d1 = dot(t.n, p1), d2 = dot(t.n, p2);
    t.lo = std::min({d0, d1, d2}), t.hi = std::max({d0, d1, d2});
    t.lim = margin * std::sqrt(dot(t.n, t.n));
    return t;
  }
  bool beyond(const Vec3f* q) const {
    const float d0 = dot(n, q[0]), d1 = dot(n, q[1]), d2 = dot(n, q[2]);
    return std::min({d0, d1, d2}) > hi + lim || std::max({d0, d1, d2}) < lo - lim;
  }
};

struct ExactScratch {
  std::vector<Vec3f> va, vb;
  std::vector<float> boxes_b;        // 6 per triangle of b near a
  std::vector<std::uint32_t> near_b;  // those triangles
  std::vector<TrianglePlane> planes_b;
};

/// Whether organs a < b touch (or come within `clearance`). Same answer on both backends.
bool organs_touch(const Stand& stand, PrototypeLibrary& lib, std::int32_t a, std::int32_t b, float clearance,
                  ExactScratch& scratch);

/// The triangle pairs that touched the last few times: tested first next time (a turn search
/// asks about the same organ pair at nearby poses many times over, and as the poses swing about
/// different axes the touching pair moves between a few places). The answer never depends on it.
struct Witness {
  static constexpr int kSlots = 8;
  static constexpr std::uint16_t kNone = 0xffff;  // also: a triangle index too large to keep
  std::uint16_t tri_a[kSlots] = {kNone, kNone, kNone, kNone, kNone, kNone, kNone, kNone};
  std::uint16_t tri_b[kSlots] = {kNone, kNone, kNone, kNone, kNone, kNone, kNone, kNone};
  std::int8_t latest = -1;  // the slot written last
  void remember(std::size_t a, std::size_t b) {
    if (a >= kNone || b >= kNone) return;
    latest = static_cast<std::int8_t>((latest + 1) % kSlots);
    tri_a[latest] = static_cast<std::uint16_t>(a), tri_b[latest] = static_cast<std::uint16_t>(b);
  }
};

/// The same test with the organs at the given plant-frame transforms instead of the stand's (the
/// turn search of resolution tries poses before it keeps one).
bool organs_touch_at(const Stand& stand, PrototypeLibrary& lib, std::int32_t a, const Affine3f& ta, std::int32_t b,
                     const Affine3f& tb, float clearance, ExactScratch& scratch, Witness* witness = nullptr);

/// The organ's vertices in the plant frame of `frame_plant` (its own frame moved by the origin
/// difference), as every exact test computes them.
void organ_vertices(const Stand& stand, const PrototypeMesh& mesh, std::int32_t organ, std::int32_t frame_plant,
                    std::vector<Vec3f>& out);
void organ_vertices(const Stand& stand, const PrototypeMesh& mesh, const Affine3f& transform, std::int32_t plant,
                    std::int32_t frame_plant, std::vector<Vec3f>& out);

/// Solids: closed cylinders and spheres contain what lies inside them.
inline bool is_solid(PrototypeKind k) { return k == PrototypeKind::cylinder || k == PrototypeKind::sphere; }

}  // namespace canopy
