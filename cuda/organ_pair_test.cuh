#pragma once
// The exact test of one organ pair by one warp, at given transforms: the detection's exact stage
// (the stand's transforms) and resolution's bulk attempts (a turned pose of one organ) share it.
// Same answer as collision/exact.cpp's organs_touch_at: the same vertices, the same closed
// triangle predicates (geometry/triangle_test.hpp, triangle_distance.hpp), the same containment
// test of solids.
#include "collision/mbvt_fit.hpp"
#include "cuda/detect_kernels.hpp"
#include "geometry/triangle_distance.hpp"
#include "geometry/triangle_reject.hpp"

namespace canopy::cuda {

/// The offset of plant q's frame in plant p's, made on the device exactly as the host makes it.
__device__ inline Vec3f offset_between(const StandView& v, std::int32_t p, std::int32_t q) {
  if (p == q) return {0, 0, 0};
  const PlantOrigin a = v.origins[p], b = v.origins[q];
  return origin_offset(a.x, a.y, b.x, b.y);
}

/// Vertex k of a mesh at transform t, in the frame of the lower organ's plant (moved by
/// `offset`), exactly as the host computes it: apply(m, p) + d.
__device__ inline Vec3f vertex(const StandView& v, const MeshRef& m, const Affine3f& t, Vec3f offset,
                               std::uint32_t k) {
  return apply(t, v.mesh_positions[m.first_vertex + k]) + offset;
}

constexpr unsigned kFullWarp = 0xffffffffu;

__device__ inline float warp_min(float x) {
  for (int o = 16; o > 0; o /= 2) x = min_f(x, __shfl_xor_sync(kFullWarp, x, o));
  return x;
}

__device__ inline float warp_max(float x) {
  for (int o = 16; o > 0; o /= 2) x = max_f(x, __shfl_xor_sync(kFullWarp, x, o));
  return x;
}

/// A warp's shared room for the staged test of two small meshes: their posed vertices, their
/// triangles' boxes, and the triangles of each that reach the other organ's box.
struct WarpStage {
  static constexpr std::uint32_t kVertices = 64, kTriangles = 64;
  Vec3f va[kVertices], vb[kVertices];
  float ba[kTriangles][6], bb[kTriangles][6];
  std::uint8_t la[kTriangles], lb[kTriangles];
};

namespace detail {

/// The lanes' share of a mesh posed into shared memory: vertices, then triangle boxes (lo, hi).
__device__ inline void stage_mesh(const StandView& v, const MeshRef& m, const Affine3f& t, Vec3f offset,
                                  Vec3f* vert, float (*box)[6]) {
  const unsigned lane = threadIdx.x % 32;
  for (std::uint32_t i = lane; i < m.vertex_count; i += 32) vert[i] = vertex(v, m, t, offset, i);
  __syncwarp();
  for (std::uint32_t i = lane; i < m.triangle_count; i += 32) {
    const std::uint32_t* idx = v.mesh_indices + m.first_index + 3 * i;
    const Vec3f p = vert[idx[0]], q = vert[idx[1]], r = vert[idx[2]];
    box[i][0] = min_f(p.x, min_f(q.x, r.x)), box[i][1] = min_f(p.y, min_f(q.y, r.y)),
    box[i][2] = min_f(p.z, min_f(q.z, r.z));
    box[i][3] = max_f(p.x, max_f(q.x, r.x)), box[i][4] = max_f(p.y, max_f(q.y, r.y)),
    box[i][5] = max_f(p.z, max_f(q.z, r.z));
  }
  __syncwarp();
}

/// The box of a staged mesh's vertices, in every lane.
__device__ inline void staged_box(const Vec3f* vert, std::uint32_t n, float lo[3], float hi[3]) {
  lo[0] = lo[1] = lo[2] = 3e38f, hi[0] = hi[1] = hi[2] = -3e38f;
  for (std::uint32_t i = threadIdx.x % 32; i < n; i += 32) {
    const Vec3f p = vert[i];
    lo[0] = min_f(lo[0], p.x), lo[1] = min_f(lo[1], p.y), lo[2] = min_f(lo[2], p.z);
    hi[0] = max_f(hi[0], p.x), hi[1] = max_f(hi[1], p.y), hi[2] = max_f(hi[2], p.z);
  }
  for (int d = 0; d < 3; ++d) lo[d] = warp_min(lo[d]), hi[d] = warp_max(hi[d]);
}

/// The triangles of a staged mesh whose box meets the box [lo, hi] with c between them (a
/// triangle that does not cannot pass the pair test against any triangle inside it): their
/// indices in `out`, their count back. `widen_own`: c is added to the triangle's box, else to
/// [lo, hi], as the pair test adds it (c on a's side), so rounding cannot drop a pair it passes.
__device__ inline std::uint32_t reaching(const float (*box)[6], std::uint32_t n, const float lo[3],
                                         const float hi[3], double c, bool widen_own, std::uint8_t* out) {
  const unsigned lane = threadIdx.x % 32;
  std::uint32_t count = 0;
  for (std::uint32_t i0 = 0; i0 < n; i0 += 32) {
    const std::uint32_t i = i0 + lane;
    bool in = i < n;
    for (int d = 0; in && d < 3; ++d)
      in = widen_own ? box[i][d] - c <= hi[d] && box[i][3 + d] + c >= lo[d]
                     : box[i][d] <= hi[d] + c && box[i][3 + d] >= lo[d] - c;
    const unsigned votes = __ballot_sync(kFullWarp, in);
    if (in) out[count + __popc(votes & ((1u << lane) - 1))] = static_cast<std::uint8_t>(i);
    count += __popc(votes);
  }
  __syncwarp();
  return count;
}

/// Whether any triangle pair of the staged meshes touches (the lanes share the pairs of the
/// triangles that reach the other mesh's box). Every lane returns the same answer.
__device__ inline bool staged_surfaces_touch(const StandView& v, const MeshRef& ma, const Affine3f& ta,
                                             const MeshRef& mb, const Affine3f& tb, Vec3f db, float clearance,
                                             WarpStage& w, std::uint32_t* found) {
  const unsigned lane = threadIdx.x % 32;
  stage_mesh(v, ma, ta, Vec3f{0, 0, 0}, w.va, w.ba);
  stage_mesh(v, mb, tb, db, w.vb, w.bb);
  const double c = clearance;
  const float margin = clearance + kRejectSlack;
  float alo[3], ahi[3], blo[3], bhi[3];
  staged_box(w.va, ma.vertex_count, alo, ahi);
  staged_box(w.vb, mb.vertex_count, blo, bhi);
  const std::uint32_t na = reaching(w.ba, ma.triangle_count, blo, bhi, c, true, w.la);
  const std::uint32_t nb = na ? reaching(w.bb, mb.triangle_count, alo, ahi, c, false, w.lb) : 0;
  for (std::uint32_t k0 = 0; k0 < na * nb; k0 += 32) {
    const std::uint32_t k = k0 + lane;
    bool hit = false;
    std::uint32_t i = 0, j = 0;
    if (k < na * nb) {
      i = w.la[k / nb], j = w.lb[k % nb];
      bool box = true;
      for (int d = 0; d < 3; ++d)
        box = box && w.bb[j][d] <= w.ba[i][3 + d] + c && w.bb[j][3 + d] >= w.ba[i][d] - c;
      if (box) {
        const std::uint32_t* ia = v.mesh_indices + ma.first_index + 3 * i;
        const std::uint32_t* ib = v.mesh_indices + mb.first_index + 3 * j;
        const Vec3f a3[3] = {w.va[ia[0]], w.va[ia[1]], w.va[ia[2]]};
        const Vec3f b3[3] = {w.vb[ib[0]], w.vb[ib[1]], w.vb[ib[2]]};
        // The host's float rejections first (collision/exact.cpp posed_touch): most pairs near
        // a contact are settled there, not in the double-precision test.
        const TrianglePlane pa = TrianglePlane::of(a3[0], a3[1], a3[2]),
                            pb = TrianglePlane::of(b3[0], b3[1], b3[2]);
        hit = !triangles_rejected(pa, a3, pb, b3, margin) &&
              (c > 0 ? triangles_within(a3, b3, c) : triangles_intersect(a3, b3));
      }
    }
    const unsigned votes = __ballot_sync(kFullWarp, hit);
    if (votes) {
      // The lowest lane that hit keeps its triangles (of a << 16 | of b) for the caller.
      if (found && lane == static_cast<unsigned>(__ffs(static_cast<int>(votes)) - 1)) *found = i << 16 | j;
      return true;
    }
  }
  return false;
}

/// Whether any triangle pair touches, vertices made as needed (meshes of any size): each lane
/// takes a's triangles in turn against all of b's; `done` is the warp's shared flag.
__device__ inline bool surfaces_touch(const StandView& v, const MeshRef& ma, const Affine3f& ta,
                                      const MeshRef& mb, const Affine3f& tb, Vec3f db, float clearance,
                                      volatile int& done) {
  const unsigned lane = threadIdx.x % 32;
  const Vec3f zero{0, 0, 0};
  // b's box, widened by the clearance: only a's triangles inside it need the full test.
  float lo[3] = {3e38f, 3e38f, 3e38f}, hi[3] = {-3e38f, -3e38f, -3e38f};
  for (std::uint32_t i = lane; i < mb.vertex_count; i += 32) {
    const Vec3f p = vertex(v, mb, tb, db, i);
    lo[0] = min_f(lo[0], p.x), lo[1] = min_f(lo[1], p.y), lo[2] = min_f(lo[2], p.z);
    hi[0] = max_f(hi[0], p.x), hi[1] = max_f(hi[1], p.y), hi[2] = max_f(hi[2], p.z);
  }
  for (int d = 0; d < 3; ++d) lo[d] = warp_min(lo[d]), hi[d] = warp_max(hi[d]);
  if (lane == 0) done = 0;
  __syncwarp();
  const double c = clearance;
  for (std::uint32_t i0 = 0; i0 < ma.triangle_count; i0 += 32) {
    const std::uint32_t i = i0 + lane;
    if (i < ma.triangle_count) {
      Vec3f a3[3];
      for (int q = 0; q < 3; ++q) a3[q] = vertex(v, ma, ta, zero, v.mesh_indices[ma.first_index + 3 * i + q]);
      const float alo[3] = {min_f(a3[0].x, min_f(a3[1].x, a3[2].x)), min_f(a3[0].y, min_f(a3[1].y, a3[2].y)),
                            min_f(a3[0].z, min_f(a3[1].z, a3[2].z))};
      const float ahi[3] = {max_f(a3[0].x, max_f(a3[1].x, a3[2].x)), max_f(a3[0].y, max_f(a3[1].y, a3[2].y)),
                            max_f(a3[0].z, max_f(a3[1].z, a3[2].z))};
      bool near = true;
      for (int d = 0; d < 3; ++d) near = near && alo[d] - c <= hi[d] && ahi[d] + c >= lo[d];
      for (std::uint32_t j = 0; near && j < mb.triangle_count && !done; ++j) {
        Vec3f b3[3];
        for (int q = 0; q < 3; ++q) b3[q] = vertex(v, mb, tb, db, v.mesh_indices[mb.first_index + 3 * j + q]);
        bool box = true;
        for (int d = 0; d < 3; ++d) {
          const float bl = d == 0   ? min_f(b3[0].x, min_f(b3[1].x, b3[2].x))
                           : d == 1 ? min_f(b3[0].y, min_f(b3[1].y, b3[2].y))
                                    : min_f(b3[0].z, min_f(b3[1].z, b3[2].z));
          const float bh = d == 0   ? max_f(b3[0].x, max_f(b3[1].x, b3[2].x))
                           : d == 1 ? max_f(b3[0].y, max_f(b3[1].y, b3[2].y))
                                    : max_f(b3[0].z, max_f(b3[1].z, b3[2].z));
          box = box && bl <= ahi[d] + c && bh >= alo[d] - c;
        }
        if (box && (c > 0 ? triangles_within(a3, b3, c) : triangles_intersect(a3, b3))) done = 1;
      }
    }
    __syncwarp();
    if (done) break;  // the same value in every lane after the sync
  }
  return done;
}

/// Whether point p lies inside the convex solid of mesh m (its vertex k is vertex_of(k)), faces
/// shared by the lanes: no face sees it outside, and one sees it strictly inside.
template <typename VertexOf>
__device__ inline bool inside_solid(const StandView& v, Vec3f p, const MeshRef& m, VertexOf vertex_of) {
  bool outer = false, inner = false;
  for (std::uint32_t f = threadIdx.x % 32; f < m.triangle_count; f += 32) {
    const std::uint32_t* idx = v.mesh_indices + m.first_index + 3 * f;
    const double o = orient3d(d3(vertex_of(idx[0])), d3(vertex_of(idx[1])), d3(vertex_of(idx[2])), d3(p));
    outer = outer || o > 0;
    inner = inner || o < 0;
  }
  return !__any_sync(kFullWarp, outer) && __any_sync(kFullWarp, inner);
}

/// Whether one organ lies wholly inside the other's solid (their vertices given by vertex_a and
/// vertex_b), for organs whose surfaces do not meet.
template <typename VertexA, typename VertexB>
__device__ inline bool one_inside_other(const StandView& v, const OrganRecord& ra, const MeshRef& ma,
                                        VertexA vertex_a, const OrganRecord& rb, const MeshRef& mb,
                                        VertexB vertex_b) {
  if (is_solid(rb.prototype) && ma.vertex_count && inside_solid(v, vertex_a(0), mb, vertex_b)) return true;
  return is_solid(ra.prototype) && mb.vertex_count && inside_solid(v, vertex_b(0), ma, vertex_a);
}

}  // namespace detail

/// Whether triangle `witness >> 16` of organ a < b and triangle `witness & 0xffff` of b touch at
/// transforms ta and tb (each in its own plant's frame), one thread: their vertices made as the
/// warp test makes them and its exact predicate, so a touch here is one the warp test finds too
/// (resolution's bulk attempts try a pair's last touching triangles before a warp's full test).
__device__ inline bool witness_touches(const StandView& v, std::uint32_t a, const Affine3f& ta,
                                       std::uint32_t b, const Affine3f& tb, std::uint32_t witness,
                                       float clearance) {
  const OrganRecord ra = v.organs[a], rb = v.organs[b];
  const MeshRef ma = v.meshes[mesh_slot(ra.prototype, ra.lod, ra.shape)];
  const MeshRef mb = v.meshes[mesh_slot(rb.prototype, rb.lod, rb.shape)];
  const std::uint32_t i = witness >> 16, j = witness & 0xffffu;
  if (i >= ma.triangle_count || j >= mb.triangle_count) return false;
  const Vec3f zero{0, 0, 0}, db = offset_between(v, ra.plant, rb.plant);
  Vec3f a3[3], b3[3];
  for (int q = 0; q < 3; ++q) {
    a3[q] = vertex(v, ma, ta, zero, v.mesh_indices[ma.first_index + 3 * i + q]);
    b3[q] = vertex(v, mb, tb, db, v.mesh_indices[mb.first_index + 3 * j + q]);
  }
  return clearance > 0 ? triangles_within(a3, b3, clearance, true) : triangles_intersect(a3, b3);
}

/// Whether organs a < b touch (within `clearance` when it is positive) at transforms ta and tb
/// (each in its own plant's frame); called by all 32 lanes of a warp, answer in every lane;
/// `done` is the warp's own shared flag. The lanes split the triangle pairs and stop together
/// once any lane finds a touching pair, since the answer is an "any" (the same answer as one
/// thread walking every pair: min and max are exact in any order, and the containment test's
/// votes are the serial loop's conjunction and disjunction); capped cylinders and spheres are
/// solids, so an organ wholly inside one touches it too.
///
/// With `stage` and meshes small enough for it, the meshes are posed once into shared memory,
/// each keeps only its triangles that reach the other's box, and the lanes share the pairs of
/// those (the same pairs pass the same box test as without, so the answer is the same); where
/// `found` is given, a touching triangle pair found there is written to it (of a << 16 | of b).
__device__ inline bool warp_organs_touch(const StandView& v, std::uint32_t a, const Affine3f& ta,
                                         std::uint32_t b, const Affine3f& tb, float clearance,
                                         volatile int& done, WarpStage* stage = nullptr,
                                         std::uint32_t* found = nullptr) {
  const OrganRecord ra = v.organs[a], rb = v.organs[b];
  const MeshRef ma = v.meshes[mesh_slot(ra.prototype, ra.lod, ra.shape)];
  const MeshRef mb = v.meshes[mesh_slot(rb.prototype, rb.lod, rb.shape)];
  const Vec3f zero{0, 0, 0};
  const Vec3f db = offset_between(v, ra.plant, rb.plant);
  // The host rejects two solids whose capsules lie apart before posing them (solids_apart,
  // collision/exact.cpp); here, where the lanes share a pair's triangles, the same test in every
  // lane makes the exact kernels slower (bench_detect_cuda: about 15 %), so the device goes
  // straight on. Same answers: the rejection is conservative.
  // Where no surfaces meet, one organ may still lie wholly inside the other's solid (tested on
  // the staged vertices where the meshes were staged: the same values as those made anew).
  if (stage && ma.vertex_count <= WarpStage::kVertices && mb.vertex_count <= WarpStage::kVertices &&
      ma.triangle_count <= WarpStage::kTriangles && mb.triangle_count <= WarpStage::kTriangles) {
    if (detail::staged_surfaces_touch(v, ma, ta, mb, tb, db, clearance, *stage, found)) return true;
    return detail::one_inside_other(
        v, ra, ma, [&](std::uint32_t k) { return stage->va[k]; }, rb, mb,
        [&](std::uint32_t k) { return stage->vb[k]; });
  }
  if (detail::surfaces_touch(v, ma, ta, mb, tb, db, clearance, done)) return true;
  return detail::one_inside_other(
      v, ra, ma, [&](std::uint32_t k) { return vertex(v, ma, ta, zero, k); }, rb, mb,
      [&](std::uint32_t k) { return vertex(v, mb, tb, db, k); });
}

}  // namespace canopy::cuda
