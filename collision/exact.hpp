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
  float lo = 0, hi = 0, length = 0;  // length: |n|
  static TrianglePlane of(Vec3f p0, Vec3f p1, Vec3f p2) {
    TrianglePlane t;
    t.n = cross(p1 - p0, p2 - p0);
    const float d0 = dot(t.n, p0), d1 = dot(t.n, p1), d2 = dot(t.n, p2);
    t.lo = std::min({d0, d1, d2}), t.hi = std::max({d0, d1, d2});
    t.length = std::sqrt(dot(t.n, t.n));
    return t;
  }
  /// Whether q lies beyond the plane by more than `margin` (margin x |n| along n).
  bool beyond(const Vec3f* q, float margin) const {
    const float lim = margin * length;
    const float d0 = dot(n, q[0]), d1 = dot(n, q[1]), d2 = dot(n, q[2]);
    return std::min({d0, d1, d2}) > hi + lim || std::max({d0, d1, d2}) < lo - lim;
  }
};

/// The same kind of float rejection on the nine axes across an edge of t and an edge of u (their
/// cross products; any axis separates by the separating-axis theorem): true when the two
/// triangles' projections lie more than `margin` x |axis| apart on one of them. The float rounding
/// of a projection (a few 1e-7 |axis| at plant-frame coordinates of metres) is far below the
/// margin's slack, so a pair rejected here is farther apart than the exact test's clearance.
inline bool apart_on_edges(const Vec3f* t, const Vec3f* u, float margin) {
  for (int i = 0; i < 3; ++i) {
    const Vec3f et = t[i == 2 ? 0 : i + 1] - t[i];
    for (int j = 0; j < 3; ++j) {
      const Vec3f n = cross(et, u[j == 2 ? 0 : j + 1] - u[j]);
      const float t0 = dot(n, t[0]), t1 = dot(n, t[1]), t2 = dot(n, t[2]);
      const float u0 = dot(n, u[0]), u1 = dot(n, u[1]), u2 = dot(n, u[2]);
      const float t_lo = std::min({t0, t1, t2}), t_hi = std::max({t0, t1, t2});
      const float u_lo = std::min({u0, u1, u2}), u_hi = std::max({u0, u1, u2});
      const float gap = std::max(u_lo - t_hi, t_lo - u_hi);
      if (gap > 0 && gap > margin * std::sqrt(dot(n, n))) return true;
    }
  }
  return false;
}

/// One organ's triangles at one pose in one plant's frame, with what the exact test derives from
/// them: the organ's box, each triangle's box and plane. Made once and tested against many organs
/// (a turn search tries one pose of a moving organ against all it must clear, and a kept organ at
/// its fixed pose against every pose tried); the numbers are those organs_touch_at makes, so the
/// answers do not depend on whether a pose was made for one test or kept for many.
struct PosedOrgan {
  std::int32_t organ = -1, frame = -1;  // which organ, in which plant's frame (-1: not posed)
  const PrototypeMesh* mesh = nullptr;
  bool solid = false;
  std::vector<Vec3f> v;                // vertices
  std::vector<float> tri_box;          // 6 per triangle: lo xyz, hi xyz
  double box[6] = {0, 0, 0, 0, 0, 0};  // the organ's box in double (not widened)
  /// Triangle i's plane, made when first asked for: most triangles of a pose never pass the
  /// box tests that come before it.
  const TrianglePlane& plane(std::size_t i) const {
    if (!plane_made_[i]) {
      const std::uint32_t* t = &mesh->indices[3 * i];
      plane_[i] = TrianglePlane::of(v[t[0]], v[t[1]], v[t[2]]);
      plane_made_[i] = 1;
    }
    return plane_[i];
  }
  /// Poses `organ` (mesh `m`) at transform `t` (plant-frame of its plant `plant`) in the frame of
  /// plant `frame_plant`.
  void pose(const Stand& s, const PrototypeMesh& m, std::int32_t organ, const Affine3f& t, std::int32_t plant,
            std::int32_t frame_plant);

 private:
  mutable std::vector<TrianglePlane> plane_;
  mutable std::vector<std::uint8_t> plane_made_;
};

/// Poses made lately, found again by stand, organ, frame and transform (bit for bit): an organ
/// meets several others in a row, and a turn search tries the organs it keeps clear against pose
/// after pose of the moving ones. Two-way set-associative, least recently used out. A pose also
/// depends on the stand's plant origins and prototypes, which stay fixed while a scratch lives
/// (one detection or one resolution round's planning).
class PoseCache {
 public:
  /// `organ` at transform `t` in the frame of plant `frame`, made now or found; `keep` (a pose
  /// returned before) is never evicted by this call.
  const PosedOrgan& get(const Stand& s, PrototypeLibrary& lib, std::int32_t organ, const Affine3f& t, std::int32_t frame,
                        const PosedOrgan* keep = nullptr);

 private:
  static constexpr std::size_t kSets = 64;
  struct Entry {
    PosedOrgan pose;
    const Stand* stand = nullptr;
    Affine3f at{};
    std::uint64_t used = 0;
  };
  std::vector<Entry> entries_ = std::vector<Entry>(2 * kSets);
  std::uint64_t clock_ = 0;
};

struct ExactScratch {
  PoseCache poses;
  std::vector<std::uint32_t> near_b;  // triangles of b near a
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

/// Whether witness triangle pairs of organs a < b touch at the given transforms (a's plant frame):
/// the quick first check of organs_touch_at, making only the six vertices of each pair.
bool witness_touches(const Stand& stand, PrototypeLibrary& lib, std::int32_t a, const Affine3f& ta, std::int32_t b,
                     const Affine3f& tb, float clearance, const Witness& witness);
/// The full test of two posed organs (a < b; b posed in a's plant's frame), remembering the
/// touching triangles in `witness` when given.
bool posed_touch(const PosedOrgan& a, const PosedOrgan& b, float clearance, ExactScratch& scratch, Witness* witness);

/// The same test as organs_touch with the organs at the given plant-frame transforms instead of
/// the stand's (the turn search of resolution tries poses before it keeps one). With a witness,
/// its triangle pairs are tried first unless the caller has just done so (`witness_tried`).
bool organs_touch_at(const Stand& stand, PrototypeLibrary& lib, std::int32_t a, const Affine3f& ta, std::int32_t b,
                     const Affine3f& tb, float clearance, ExactScratch& scratch, Witness* witness = nullptr,
                     bool witness_tried = false);

/// The organ's vertices in the plant frame of `frame_plant` (its own frame moved by the origin
/// difference), as every exact test computes them.
void organ_vertices(const Stand& stand, const PrototypeMesh& mesh, std::int32_t organ, std::int32_t frame_plant,
                    std::vector<Vec3f>& out);
void organ_vertices(const Stand& stand, const PrototypeMesh& mesh, const Affine3f& transform, std::int32_t plant,
                    std::int32_t frame_plant, std::vector<Vec3f>& out);

/// Solids: closed cylinders and spheres contain what lies inside them.
inline bool is_solid(PrototypeKind k) { return k == PrototypeKind::cylinder || k == PrototypeKind::sphere; }

}  // namespace canopy
