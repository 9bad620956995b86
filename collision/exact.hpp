#pragma once
/// The exact level for one organ pair on the host: two solids whose capsules lie apart are
/// rejected first (geometry/solid_bound.hpp); otherwise the organs' triangles made on the fly from
/// prototype x transform (the higher organ moved into the lower organ's plant frame by the
/// origin difference), filters of single triangles (the other organ's box, then its OBB) and of
/// triangle pairs (box, planes, edge axes), then the shared closed triangle test; capped
/// cylinders and spheres are solids, so an organ wholly inside one counts too.
#include "collision/lanes/isa.hpp"
#include "geometry/line_aligned.hpp"
#include "geometry/obb.hpp"
#include "geometry/prototype.hpp"
#include "geometry/triangle_reject.hpp"
#include "geometry/stand.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <vector>

namespace canopy {

/// One organ's triangles at one pose in one plant's frame, with what the exact test derives from
/// them: the organ's box, each triangle's box and plane. Made once and tested against many organs
/// (a turn search tries one pose of a moving organ against all it must clear, and a kept organ at
/// its fixed pose against every pose tried); the numbers are those organs_touch_at makes, so the
/// answers do not depend on whether a pose was made for one test or kept for many.
struct PosedOrgan {
  std::int32_t organ = -1, frame = -1;  // which organ, in which plant's frame (-1: not posed)
  const PrototypeMesh* mesh = nullptr;
  bool solid = false;
  /// The triangles by groups of 8 in lanes (collision/lanes/lanes8.hpp), made 8 at a time and tested
  /// 8 at a time: per group 9 lanes of corner coordinates (first corner x y z, second, third),
  /// each corner apply(transform, vertex) + origin difference as organ_vertices makes it, and 6
  /// of the triangle's box (lo x y z, hi x y z); lanes past the last triangle are not used.
  LineAlignedVector<float> tri_lanes;
  static constexpr std::size_t kGroupFloats = 15 * 8;
  /// Component k (lo x y z, hi x y z) of triangle i's box.
  float tri_box(std::size_t i, int k) const {
    return tri_lanes[i / 8 * kGroupFloats + static_cast<std::size_t>(9 + k) * 8 + i % 8];
  }
  /// Triangle i's corners.
  void corners(std::size_t i, Vec3f* out) const {
    const float* g = &tri_lanes[i / 8 * kGroupFloats + i % 8];
    for (int c = 0; c < 3; ++c) out[c] = {g[8 * (3 * c)], g[8 * (3 * c + 1)], g[8 * (3 * c + 2)]};
  }
  double box[6] = {0, 0, 0,
                   0, 0, 0};  // the organ's box in double (not widened): its corners' (every vertex is one)
  Obb obb{};                  // its OBB in this frame (make_obb, centre moved by the origin difference)
  /// Triangle i's plane, made when first asked for: most triangles of a pose never pass the
  /// box tests that come before it.
  const TrianglePlane& plane(std::size_t i) const {
    if (plane_stamp_[i] != stamp_) {
      Vec3f t[3];
      corners(i, t);
      plane_[i] = TrianglePlane::of(t[0], t[1], t[2]);
      plane_stamp_[i] = stamp_;
    }
    return plane_[i];
  }
  /// The vertices (organ_vertices), made when first asked for: only the test of an organ
  /// wholly inside a solid reads them.
  const std::vector<Vec3f>& vertices() const;
  /// Vertex 0 alone, as vertices() makes it (the point a test of containment takes).
  Vec3f first_vertex() const { return apply(at_, mesh->positions[0]) + moved_; }
  /// Poses `organ` (mesh `m`) at transform `t` (plant-frame of its plant `plant`) in the frame of
  /// plant `frame_plant`, with the fastest build this CPU runs (collision/lanes/isa.hpp).
  /// `made`, where given, is make_obb(t, m.box, 0) made before (the tree's OBB of the organ at
  /// the stand's pose, when the tree is not inflated): taken instead of made again.
  void pose(const Stand& s, const PrototypeMesh& m, std::int32_t organ, const Affine3f& t, std::int32_t plant,
            std::int32_t frame_plant, const Obb* made = nullptr) {
    pose_as(fastest_isa(), s, m, organ, t, plant, frame_plant, made);
  }
  /// pose() with the given build (Isa::x86_64_v4 only where cpu_has_x86_64_v4()): the same bits.
  void pose_as(Isa isa, const Stand& s, const PrototypeMesh& m, std::int32_t organ, const Affine3f& t,
               std::int32_t plant, std::int32_t frame_plant, const Obb* made = nullptr);

 private:
  void pose_body(const Stand& s, const PrototypeMesh& m, std::int32_t organ, const Affine3f& t,
                 std::int32_t plant, std::int32_t frame_plant, const Obb* made);
  void pose_v4(const Stand& s, const PrototypeMesh& m, std::int32_t organ, const Affine3f& t,
               std::int32_t plant, std::int32_t frame_plant, const Obb* made);
  void pose_build_target(const Stand& s, const PrototypeMesh& m, std::int32_t organ, const Affine3f& t,
                         std::int32_t plant, std::int32_t frame_plant, const Obb* made);

  Affine3f at_{};
  Vec3f moved_{};
  mutable std::vector<Vec3f> v_;
  mutable bool v_made_ = false;
  mutable std::vector<TrianglePlane> plane_;
  /// plane_[i] was made for this pose where plane_stamp_[i] == stamp_: each pose takes a new
  /// stamp instead of clearing a flag per triangle (a call to memset per pose shows in profiles
  /// of bench_detect: about 0.8 % of the samples).
  mutable std::vector<std::uint32_t> plane_stamp_;
  std::uint32_t stamp_ = 0;
};

/// Poses made lately, found again by stand, organ, frame and transform (bit for bit): an organ
/// meets several others in a row, and a turn search tries the organs it keeps clear against pose
/// after pose of the moving ones. Two-way set-associative, least recently used out. A pose also
/// depends on the stand's plant origins and prototypes, which stay fixed while a scratch lives
/// (one detection or one resolution round's planning).
class PoseCache {
 public:
  /// A turn search's size: the organs it keeps clear are tried against pose after pose.
  static constexpr std::size_t kSearchSets = 64;
  /// Detection's: its organ pairs come in the pass's order, where the lower organ repeats over a
  /// row of pairs and the higher seldom comes back soon, so two poses find nearly as many as
  /// 128 while their memory stays in the first-level cache (bench_detect: the exact stage about
  /// 9 % faster than with 128).
  static constexpr std::size_t kDetectionSets = 1;
  /// `sets` sets of two poses each (at least one; rounded up to a power of two, so that a set is
  /// found by a mask rather than a division on every lookup).
  explicit PoseCache(std::size_t sets = kSearchSets)
      : set_mask_(std::bit_ceil(std::max<std::size_t>(sets, 1)) - 1), entries_(2 * (set_mask_ + 1)) {}
  /// `organ` at transform `t` in the frame of plant `frame`, made now or found; `keep` (a pose
  /// returned before) is never evicted by this call; `made` as PosedOrgan::pose takes it.
  const PosedOrgan& get(const Stand& s, PrototypeLibrary& lib, std::int32_t organ, const Affine3f& t,
                        std::int32_t frame, const PosedOrgan* keep = nullptr, const Obb* made = nullptr);
  /// Forgets every pose (nothing is found again) and keeps the poses' memory for the next ones.
  void forget() {
    for (Entry& e : entries_) e.stand = nullptr, e.pose.organ = -1, e.used = 0;
    clock_ = 0;
  }

 private:
  struct Entry {
    PosedOrgan pose;
    const Stand* stand = nullptr;
    Affine3f at{};
    std::uint64_t used = 0;
  };
  std::size_t set_mask_;  // sets - 1
  std::vector<Entry> entries_;
  std::uint64_t clock_ = 0;
};

/// One thread's working memory for exact tests. Aligned to a cache line: threads keep theirs
/// side by side in a vector, and the pose cache's clock changes on every test.
struct alignas(64) ExactScratch {
  /// `pose_sets`: the pose cache's size (PoseCache).
  explicit ExactScratch(std::size_t pose_sets = PoseCache::kSearchSets) : poses(pose_sets) {}
  PoseCache poses;
  std::vector<std::uint8_t> near_a_bits, near_b_bits;  // a bit per triangle near the other organ, 8 per byte
};

/// Whether organs a < b touch (or come within `clearance`). Same answer on both backends.
/// `obbs`, where given, holds make_obb(transform, mesh box, 0) of every organ at the stand's
/// pose (a tree fit with no clearance: Mbvt::obbs), which the poses then take rather than make.
bool organs_touch(const Stand& stand, PrototypeLibrary& lib, std::int32_t a, std::int32_t b, float clearance,
                  ExactScratch& scratch, const Obb* obbs = nullptr);

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
  /// The slot holding triangles (a, b), or -1.
  int slot_of(std::uint16_t a, std::uint16_t b) const {
    for (int k = 0; k < kSlots; ++k)
      if (tri_a[k] == a && tri_b[k] == b) return k;
    return -1;
  }
  /// Makes slot k the newest (it swaps places with the newest): the pair found touching again.
  void promote(int k) {
    if (k == latest || k < 0) return;
    std::swap(tri_a[k], tri_a[latest]);
    std::swap(tri_b[k], tri_b[latest]);
  }
};

/// The slot of the newest witness triangle pair of organs a < b that touches at the given
/// transforms (a's plant frame), or -1: the quick first check of organs_touch_at, making only
/// the six vertices of each pair. Slot `skip` is passed over (one the caller has just seen miss
/// at these transforms).
int witness_slot_touching(const Stand& stand, PrototypeLibrary& lib, std::int32_t a, const Affine3f& ta,
                          std::int32_t b, const Affine3f& tb, float clearance, const Witness& witness,
                          int skip = -1);
/// The full test of two posed organs (a < b; b posed in a's plant's frame), remembering the
/// touching triangles in `witness` when given; with the fastest build this CPU runs
/// (collision/lanes/isa.hpp).
bool posed_touch(const PosedOrgan& a, const PosedOrgan& b, float clearance, ExactScratch& scratch,
                 Witness* witness);
/// posed_touch with the given build (Isa::x86_64_v4 only where cpu_has_x86_64_v4()): the same
/// answer and witness.
bool posed_touch_as(Isa isa, const PosedOrgan& a, const PosedOrgan& b, float clearance, ExactScratch& scratch,
                    Witness* witness);

/// The same test as organs_touch with the organs at the given plant-frame transforms instead of
/// the stand's (the turn search of resolution tries poses before it keeps one). With a witness,
/// its triangle pairs are tried first unless the caller has just done so (`witness_tried`).
bool organs_touch_at(const Stand& stand, PrototypeLibrary& lib, std::int32_t a, const Affine3f& ta,
                     std::int32_t b, const Affine3f& tb, float clearance, ExactScratch& scratch,
                     Witness* witness = nullptr, bool witness_tried = false);

/// organs_touch_at for two organs in either order: the test runs with the lower id first (its
/// plant's frame, its witness order), as every caller must.
inline bool organs_touch_either(const Stand& stand, PrototypeLibrary& lib, std::int32_t x, const Affine3f& tx,
                                std::int32_t y, const Affine3f& ty, float clearance, ExactScratch& scratch,
                                Witness* witness = nullptr, bool witness_tried = false) {
  return x < y ? organs_touch_at(stand, lib, x, tx, y, ty, clearance, scratch, witness, witness_tried)
               : organs_touch_at(stand, lib, y, ty, x, tx, clearance, scratch, witness, witness_tried);
}

/// The organ's vertices in the plant frame of `frame_plant` (its own frame moved by the origin
/// difference), as every exact test computes them.
void organ_vertices(const Stand& stand, const PrototypeMesh& mesh, std::int32_t organ,
                    std::int32_t frame_plant, std::vector<Vec3f>& out);
void organ_vertices(const Stand& stand, const PrototypeMesh& mesh, const Affine3f& transform,
                    std::int32_t plant, std::int32_t frame_plant, std::vector<Vec3f>& out);

}  // namespace canopy
