#include "collision/exact.hpp"

#include "collision/lanes/lanes8.hpp"
#include "collision/lanes/triangle_lanes.hpp"
#include "collision/mbvt.hpp"
#include "geometry/solid_bound.hpp"
#include "geometry/triangle_distance.hpp"

#include <algorithm>
#include <cassert>
#include <cstring>
#include <limits>

namespace canopy {
namespace {

/// Indices 0..count-1 in the order start, start+1, start-1, start+2, ... (wrapping): triangles
/// of neighbouring indices lie side by side on a prototype mesh, so a search that starts at the
/// triangle that touched last meets its neighbours on both sides first.
struct Spiral {
  std::size_t count, up, down, n = 0;
  Spiral(std::size_t start, std::size_t count_) : count(count_), up(start), down(start) {}
  std::size_t next() {
    // n-th index: start, then start + k and start - k for k = 1, 2, ...
    if (n++ == 0) return up;
    if (n % 2 == 0) return up = up + 1 == count ? 0 : up + 1;
    return down = down == 0 ? count - 1 : down - 1;
  }
};

}  // namespace

void organ_vertices(const Stand& s, const PrototypeMesh& mesh, std::int32_t organ, std::int32_t frame_plant,
                    std::vector<Vec3f>& out) {
  organ_vertices(s, mesh, s.transforms[static_cast<std::size_t>(organ)],
                 s.organs[static_cast<std::size_t>(organ)].plant, frame_plant, out);
}

namespace {

/// The offset from plant `plant`'s frame to `frame_plant`'s (zero within one plant).
Vec3f frame_offset(const Stand& s, std::int32_t plant, std::int32_t frame_plant) {
  return plant == frame_plant ? Vec3f{0, 0, 0} : plant_offset(s, frame_plant, plant);
}

void moved_vertices(const PrototypeMesh& mesh, const Affine3f& m, Vec3f d, std::vector<Vec3f>& out) {
  out.resize(mesh.positions.size());
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) out[i] = apply(m, mesh.positions[i]) + d;
}

}  // namespace

void organ_vertices(const Stand& s, const PrototypeMesh& mesh, const Affine3f& m, std::int32_t plant,
                    std::int32_t frame_plant, std::vector<Vec3f>& out) {
  moved_vertices(mesh, m, frame_offset(s, plant, frame_plant), out);
}

namespace {

/// organs_touch_at's test, the poses taking `made_a` / `made_b` (PosedOrgan::pose) where given.
bool touch_at(const Stand& s, PrototypeLibrary& lib, std::int32_t a, const Affine3f& pose_a, std::int32_t b,
              const Affine3f& pose_b, float clearance, ExactScratch& x, Witness* witness, bool witness_tried,
              const Obb* made_a, const Obb* made_b) {
  assert(a < b);
  const OrganRecord& ra = s.organs[static_cast<std::size_t>(a)];
  const OrganRecord& rb = s.organs[static_cast<std::size_t>(b)];
  if (solids_apart(ra.prototype, pose_a, rb.prototype, pose_b, frame_offset(s, rb.plant, ra.plant),
                   clearance))
    return false;
  if (witness && !witness_tried) {
    const int slot = witness_slot_touching(s, lib, a, pose_a, b, pose_b, clearance, *witness);
    if (slot >= 0) return witness->promote(slot), true;
  }
  const PosedOrgan& pa = x.poses.get(s, lib, a, pose_a, ra.plant, nullptr, made_a);
  const PosedOrgan& pb = x.poses.get(s, lib, b, pose_b, ra.plant, &pa, made_b);
  return posed_touch(pa, pb, clearance, x, witness);
}

}  // namespace

bool organs_touch(const Stand& s, PrototypeLibrary& lib, std::int32_t a, std::int32_t b, float clearance,
                  ExactScratch& x, const Obb* obbs) {
  const auto ia = static_cast<std::size_t>(a), ib = static_cast<std::size_t>(b);
  return touch_at(s, lib, a, s.transforms[ia], b, s.transforms[ib], clearance, x, nullptr, false,
                  obbs ? &obbs[ia] : nullptr, obbs ? &obbs[ib] : nullptr);
}

// The body of pose(), built into both builds (collision/lanes/isa.hpp).
[[gnu::always_inline]] inline void PosedOrgan::pose_body(const Stand& s, const PrototypeMesh& m,
                                                         std::int32_t id, const Affine3f& t,
                                                         std::int32_t plant, std::int32_t frame_plant,
                                                         const Obb* made) {
  organ = id, frame = frame_plant, mesh = &m;
  solid = is_solid(s.organs[static_cast<std::size_t>(id)].prototype);
  const Vec3f d = frame_offset(s, plant, frame_plant);
  at_ = t, moved_ = d, v_made_ = false;
  obb = made ? *made : make_obb(t, m.box, 0);
  if (plant != frame_plant) obb.centre = obb.centre + d;
  const std::size_t tris = m.triangle_count();
  plane_.resize(tris);
  plane_stamp_.resize(tris);  // new entries 0, never a pose's stamp
  if (++stamp_ == 0) {        // the stamps ran round: start again
    std::fill(plane_stamp_.begin(), plane_stamp_.end(), 0u);
    stamp_ = 1;
  }
  // The corners 8 triangles at a time from the mesh's corners in lanes, with the operations of
  // apply(t, p) + d in their order (so each equals organ_vertices' vertex bit for bit), then each
  // triangle's box, min_f and max_f of its corners.
  using namespace lanes_detail;
  const std::size_t groups = (tris + 7) / 8;
  tri_lanes.resize(groups * kGroupFloats);
  const float cols[3][3] = {{t.c0.x, t.c0.y, t.c0.z}, {t.c1.x, t.c1.y, t.c1.z}, {t.c2.x, t.c2.y, t.c2.z}};
  const float shift[3] = {t.t.x, t.t.y, t.t.z}, move[3] = {d.x, d.y, d.z};
  // The organ's box: the least and greatest corner (every vertex is a corner of a triangle:
  // tests/geometry), the lanes past the last triangle left out.
  F8 organ_lo[3], organ_hi[3];
  for (int k = 0; k < 3; ++k)
    organ_lo[k] = splat8(std::numeric_limits<float>::infinity()),
    organ_hi[k] = splat8(-std::numeric_limits<float>::infinity());
  for (std::size_t g = 0; g < groups; ++g) {
    const float* local = &m.corner_lanes[g * PrototypeMesh::kCornerGroupFloats];
    float* group = &tri_lanes[g * kGroupFloats];
    F8 at[3][3];  // corner, coordinate
    for (int c = 0; c < 3; ++c) {
      const F8 x = load8(local + 24 * c), y = load8(local + 24 * c + 8), z = load8(local + 24 * c + 16);
      for (int k = 0; k < 3; ++k) {
        // Stored from a register (a copy out of the array went through the stack 16 bytes at a time).
        const F8 v = cols[0][k] * x + cols[1][k] * y + cols[2][k] * z + shift[k] + move[k];
        store8(group + 8 * (3 * c + k), v);
        at[c][k] = v;
      }
    }
    // Lanes below the triangle count (a compare of the lane numbers, not a mask built lane by lane).
    const I8 in_use = I8{0, 1, 2, 3, 4, 5, 6, 7} < static_cast<int>(std::min<std::size_t>(tris - 8 * g, 8));
    for (int k = 0; k < 3; ++k) {
      const F8 box_lo = min8(at[0][k], min8(at[1][k], at[2][k])),
               box_hi = max8(at[0][k], max8(at[1][k], at[2][k]));
      store8(group + 8 * (9 + k), box_lo);
      store8(group + 8 * (12 + k), box_hi);
      // As std::min and std::max take a new value (a NaN one leaves the box as it was).
      organ_lo[k] = in_use ? min8(box_lo, organ_lo[k]) : organ_lo[k];
      organ_hi[k] = in_use ? max8(box_hi, organ_hi[k]) : organ_hi[k];
    }
  }
  box[0] = box[1] = box[2] = 1e300, box[3] = box[4] = box[5] = -1e300;
  if (groups > 0)
    for (int k = 0; k < 3; ++k) {
      box[k] = least8(organ_lo[k]), box[k + 3] = greatest8(organ_hi[k]);
    }
}

CANOPY_TARGET_V4 void PosedOrgan::pose_v4(const Stand& s, const PrototypeMesh& m, std::int32_t id,
                                          const Affine3f& t, std::int32_t plant, std::int32_t frame_plant,
                                          const Obb* made) {
  pose_body(s, m, id, t, plant, frame_plant, made);
}

void PosedOrgan::pose_build_target(const Stand& s, const PrototypeMesh& m, std::int32_t id, const Affine3f& t,
                                   std::int32_t plant, std::int32_t frame_plant, const Obb* made) {
  pose_body(s, m, id, t, plant, frame_plant, made);
}

void PosedOrgan::pose_as(Isa isa, const Stand& s, const PrototypeMesh& m, std::int32_t id, const Affine3f& t,
                         std::int32_t plant, std::int32_t frame_plant, const Obb* made) {
  if (isa == Isa::x86_64_v4) pose_v4(s, m, id, t, plant, frame_plant, made);
  else pose_build_target(s, m, id, t, plant, frame_plant, made);
}

const std::vector<Vec3f>& PosedOrgan::vertices() const {
  if (!v_made_) {
    moved_vertices(*mesh, at_, moved_, v_);
    v_made_ = true;
  }
  return v_;
}

namespace {

/// A bit per triangle of `p` (8 per byte): near_lanes against the other organ's box and OBB.
/// Whether any is set.
bool near_bits(const PosedOrgan& p, const FloatBounds& box, const Obb& obb, float margin,
               std::vector<std::uint8_t>& bits) {
  const std::size_t tris = p.mesh->triangle_count(), groups = (tris + 7) / 8;
  bits.resize(groups);
  unsigned any = 0;
  for (std::size_t g = 0; g < groups; ++g)
    any |= bits[g] = static_cast<std::uint8_t>(
        near_lanes(&p.tri_lanes[g * PosedOrgan::kGroupFloats], box, obb, margin) &
        lanes_detail::lanes_below(static_cast<std::uint32_t>(tris), static_cast<std::uint32_t>(8 * g)));
  return any != 0;
}

bool bit(const std::vector<std::uint8_t>& bits, std::size_t i) { return (bits[i / 8] >> (i % 8)) & 1u; }

/// Whether the boxes of triangles p and q lie more than c apart along x, y or z (in double, as
/// posed_touch compares a triangle's box with the other organ's widened box).
bool boxes_apart(const Vec3f* p, const Vec3f* q, double c) {
  for (int k = 0; k < 3; ++k) {
    const auto lo_hi = [k](const Vec3f* t, float& lo, float& hi) {
      const auto at = [k](const Vec3f& v) { return k == 0 ? v.x : k == 1 ? v.y : v.z; };
      lo = std::min(at(t[0]), std::min(at(t[1]), at(t[2]))),
      hi = std::max(at(t[0]), std::max(at(t[1]), at(t[2])));
    };
    float plo, phi, qlo, qhi;
    lo_hi(p, plo, phi), lo_hi(q, qlo, qhi);
    if (static_cast<double>(plo) > static_cast<double>(qhi) + c ||
        static_cast<double>(qlo) > static_cast<double>(phi) + c)
      return true;
  }
  return false;
}

}  // namespace

int witness_slot_touching(const Stand& s, PrototypeLibrary& lib, std::int32_t a, const Affine3f& pose_a,
                          std::int32_t b, const Affine3f& pose_b, float clearance, const Witness& w,
                          int skip) {
  const OrganRecord& ra = s.organs[static_cast<std::size_t>(a)];
  const OrganRecord& rb = s.organs[static_cast<std::size_t>(b)];
  const PrototypeMesh& ma = lib.get(ra);
  const PrototypeMesh& mb = lib.get(rb);
  const std::size_t ta = ma.triangle_count(), tb = mb.triangle_count();
  const Vec3f d = frame_offset(s, rb.plant, ra.plant);
  // Newest first, the six vertices made as organ_vertices makes them. The newest pair is the
  // likeliest to touch still (the intersection test first); an older one, to miss (the quick
  // rejections first): the same answers, 1.5 % fewer instructions in resolution than either
  // order throughout.
  for (int n = 0; n < Witness::kSlots; ++n) {
    const int slot = (w.latest - n + Witness::kSlots) % Witness::kSlots;
    if (slot == skip) continue;
    const std::size_t wa = w.tri_a[slot], wb = w.tri_b[slot];
    if (wa >= ta || wb >= tb) continue;
    Vec3f p[3], q[3];
    for (int k = 0; k < 3; ++k) {
      p[k] = apply(pose_a, ma.positions[ma.indices[3 * wa + static_cast<std::size_t>(k)]]) + Vec3f{0, 0, 0};
      q[k] = apply(pose_b, mb.positions[mb.indices[3 * wb + static_cast<std::size_t>(k)]]) + d;
    }
    // The triangles' boxes first, as posed_touch filters triangles by box: most witnesses of a
    // pose a few degrees on are clear of each other by more than the clearance.
    if (boxes_apart(p, q, clearance)) continue;
    if (clearance > 0 ? triangles_within(p, q, clearance, n == 0) : triangles_intersect(p, q)) return slot;
  }
  return -1;
}

bool organs_touch_at(const Stand& s, PrototypeLibrary& lib, std::int32_t a, const Affine3f& pose_a,
                     std::int32_t b, const Affine3f& pose_b, float clearance, ExactScratch& x,
                     Witness* witness, bool witness_tried) {
  return touch_at(s, lib, a, pose_a, b, pose_b, clearance, x, witness, witness_tried, nullptr, nullptr);
}

const PosedOrgan& PoseCache::get(const Stand& s, PrototypeLibrary& lib, std::int32_t organ, const Affine3f& t,
                                 std::int32_t frame, const PosedOrgan* keep, const Obb* made) {
  const std::size_t set =
      (static_cast<std::size_t>(organ) * 0x9E3779B1u ^ static_cast<std::size_t>(frame)) & set_mask_;
  Entry* way = &entries_[2 * set];
  ++clock_;
  for (int w = 0; w < 2; ++w)
    if (way[w].pose.organ == organ && way[w].pose.frame == frame && way[w].stand == &s &&
        std::memcmp(&way[w].at, &t, sizeof t) == 0) {
      way[w].used = clock_;
      return way[w].pose;
    }
  // Out goes the older way, unless it holds `keep`.
  int w = way[0].used <= way[1].used ? 0 : 1;
  if (&way[w].pose == keep) w ^= 1;
  Entry& e = way[w];
  const OrganRecord& r = s.organs[static_cast<std::size_t>(organ)];
  e.pose.pose(s, lib.get(r), organ, t, r.plant, frame, made);
  e.stand = &s;
  e.at = t;
  e.used = clock_;
  return e.pose;
}

namespace {

// The body of posed_touch, built into both builds (collision/lanes/isa.hpp).
[[gnu::always_inline]] inline bool posed_touch_body(const PosedOrgan& pa, const PosedOrgan& pb,
                                                    float clearance, ExactScratch& x, Witness* witness) {
  assert(pa.organ < pb.organ && pa.frame == pb.frame);
  const PrototypeMesh& ma = *pa.mesh;
  const PrototypeMesh& mb = *pb.mesh;
  const std::size_t ta = ma.triangle_count(), tb = mb.triangle_count();
  const double c = clearance;
  // Only triangles inside the other organ's box widened by the clearance can meet anything of
  // it; of those, only the ones not beyond its OBB by the margin below (beyond_obb).
  double box_a[6], box_b[6];
  for (int k = 0; k < 3; ++k) {
    box_a[k] = pa.box[k] - c, box_a[k + 3] = pa.box[k + 3] + c;
    box_b[k] = pb.box[k] - c, box_b[k + 3] = pb.box[k + 3] + c;
  }
  // The float tests below (beyond_obb, triangles_rejected) reject only triangles or pairs more
  // than this beyond the clearance.
  const float margin = static_cast<float>(c) + kRejectSlack;
  const auto pair_touches = [&](const Vec3f* p, const Vec3f* q) {
    return c > 0 ? triangles_within(p, q, c) : triangles_intersect(p, q);
  };
  // With a witness, start both loops at its triangles: a touching pair is likely near the one
  // that touched last (the answer is the same in any order).
  const bool seen = witness && witness->latest >= 0 && witness->tri_a[witness->latest] < ta &&
                    witness->tri_b[witness->latest] < tb;
  const std::size_t start_a = seen ? static_cast<std::size_t>(witness->tri_a[witness->latest]) : 0;
  const std::size_t start_b = seen ? static_cast<std::size_t>(witness->tri_b[witness->latest]) : 0;
  // The triangles of each organ near the other, 8 at a time. Then a's near triangles one by
  // one (from the witness's outwards), each against b's near ones 8 at a time (their groups
  // from the witness's on): the pair's boxes, then the float rejections (triangles_rejected),
  // then the exact test on the pairs left, in lane order.
  const std::size_t groups_b = (tb + 7) / 8;
  if (near_bits(pb, FloatBounds(box_a), pa.obb, margin, x.near_b_bits) &&
      near_bits(pa, FloatBounds(box_b), pb.obb, margin, x.near_a_bits)) {
    Spiral order_a(start_a, ta);
    for (std::size_t ii = 0; ii < ta; ++ii) {
      const std::size_t i = order_a.next();
      if (!bit(x.near_a_bits, i)) continue;
      Vec3f tri_a[3];
      pa.corners(i, tri_a);
      // Box of a's triangle, widened by the clearance in double (exact for touching boxes).
      double box_i[6];
      for (int k = 0; k < 3; ++k) box_i[k] = pa.tri_box(i, k) - c, box_i[k + 3] = pa.tri_box(i, k + 3) + c;
      // With no clearance the widened box is the float box itself (the same bounds, without
      // the conversions and nextafter tests).
      const FloatBounds bounds_i = c == 0 ? FloatBounds::of_floats(box_i) : FloatBounds(box_i);
      for (std::size_t gg = 0; gg < groups_b; ++gg) {
        const std::size_t g = (start_b / 8 + gg) % groups_b;
        const float* group = &pb.tri_lanes[g * PosedOrgan::kGroupFloats];
        unsigned lanes = x.near_b_bits[g];
        if (lanes) lanes &= boxes_meeting_lanes(group, bounds_i);
        if (lanes) lanes &= ~rejected_lanes(pa.plane(i), tri_a, group, margin, lanes);
        for (; lanes; lanes &= lanes - 1) {
          const std::size_t j = 8 * g + static_cast<std::size_t>(__builtin_ctz(lanes));
          Vec3f tri_b[3];
          pb.corners(j, tri_b);
          if (pair_touches(tri_a, tri_b)) {
            if (witness) witness->remember(i, j);
            return true;
          }
        }
      }
    }
  }
  // No surfaces meet: one organ may still lie wholly inside the other's solid, which its vertex
  // 0 tells. A vertex beyond the solid's OBB by the margin lies outside it (beyond_obb's
  // reasoning, the point taken as a triangle of three equal corners), so the solid's vertices
  // are made only for a vertex within (making them for every pair whose surfaces miss costs the
  // query time: bench_detect, about 1.5 %).
  const auto inside = [margin](const PosedOrgan& solid, std::size_t solid_tris, const PosedOrgan& other) {
    const Vec3f p = other.first_vertex();
    const Vec3f point[3] = {p, p, p};
    return !beyond_obb(point, solid.obb, margin) &&
           point_in_convex(d3(p), solid.vertices().data(), solid.mesh->indices.data(),
                           static_cast<int>(solid_tris));
  };
  if (pb.solid && ta > 0 && inside(pb, tb, pa)) return true;
  if (pa.solid && tb > 0 && inside(pa, ta, pb)) return true;
  return false;
}

CANOPY_TARGET_V4 bool posed_touch_v4(const PosedOrgan& pa, const PosedOrgan& pb, float clearance,
                                     ExactScratch& x, Witness* witness) {
  return posed_touch_body(pa, pb, clearance, x, witness);
}

bool posed_touch_build_target(const PosedOrgan& pa, const PosedOrgan& pb, float clearance, ExactScratch& x,
                              Witness* witness) {
  return posed_touch_body(pa, pb, clearance, x, witness);
}

}  // namespace

bool posed_touch_as(Isa isa, const PosedOrgan& pa, const PosedOrgan& pb, float clearance, ExactScratch& x,
                    Witness* witness) {
  return isa == Isa::x86_64_v4 ? posed_touch_v4(pa, pb, clearance, x, witness)
                               : posed_touch_build_target(pa, pb, clearance, x, witness);
}

bool posed_touch(const PosedOrgan& pa, const PosedOrgan& pb, float clearance, ExactScratch& x,
                 Witness* witness) {
  return posed_touch_as(fastest_isa(), pa, pb, clearance, x, witness);
}

}  // namespace canopy
