#pragma once
/// The exact level for one organ pair on the host: the organs' triangles made on the fly from
/// prototype x transform (the higher organ moved into the lower organ's plant frame by the
/// origin difference), a triangle-box filter, then the shared closed triangle test; capped
/// cylinders and spheres are solids, so an organ wholly inside one counts too.
#include "geometry/prototype.hpp"
#include "geometry/stand.hpp"

#include <vector>

namespace canopy {

struct ExactScratch {
  std::vector<Vec3f> va, vb;
  std::vector<float> boxes_b;        // 6 per triangle of b near a
  std::vector<std::uint32_t> near_b;  // those triangles
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
  std::uint16_t tri_a[kSlots] = {kNone, kNone, kNone, kNone, kNone, kNone, kNone, kNone}, tri_b[kSlots] = {kNone, kNone, kNone, kNone, kNone, kNone, kNone, kNone};
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
