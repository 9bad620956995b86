#pragma once
/// Joints for resolution: an organ turns about its joint (its attachment point, the translation
/// of its grown transform) and carries its whole subtree of the structure tree with it. Each
/// turned organ k holds a local rotation Q_k about its grown joint j_k, expressed in its parent's
/// grown frame, so the rigid motion that takes grown poses to current ones is
///   D_k = D_parent(k) o J_k,   J_k = rotation Q_k about j_k  (identity where k never turned),
/// and the current transform is T_k = D_k o G_k (G the grown transform). The joint angle |Q_k|
/// is what the joint limit bounds (DESIGN.md "Organs": at most joint_limit degrees from the
/// grown orientation). Organs under no turned joint keep their grown transform bit for bit.
#include "geometry/stand.hpp"

#include <cstdint>
#include <vector>

namespace canopy {

/// Row-major 3x3 rotation in double.
struct Mat3d {
  double m[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
};
// The small products are inline: the turn search makes millions of them.
inline Mat3d operator*(const Mat3d& a, const Mat3d& b) {
  Mat3d c;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) c.m[3 * i + j] = a.m[3 * i] * b.m[j] + a.m[3 * i + 1] * b.m[3 + j] + a.m[3 * i + 2] * b.m[6 + j];
  return c;
}
inline Vec3d operator*(const Mat3d& a, Vec3d v) {
  return {a.m[0] * v.x + a.m[1] * v.y + a.m[2] * v.z, a.m[3] * v.x + a.m[4] * v.y + a.m[5] * v.z,
          a.m[6] * v.x + a.m[7] * v.y + a.m[8] * v.z};
}
inline Mat3d transpose(const Mat3d& a) {
  Mat3d t;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) t.m[3 * i + j] = a.m[3 * j + i];
  return t;
}
/// Rodrigues' formula: rotation by `angle` radians about the unit `axis`.
Mat3d axis_angle(Vec3d axis, double angle);
/// The same with the angle's cosine and sine given (many axes turned by one angle).
inline Mat3d axis_angle(Vec3d k, double c, double s) {
  const double v = 1 - c;
  Mat3d r;
  r.m[0] = c + k.x * k.x * v, r.m[1] = k.x * k.y * v - k.z * s, r.m[2] = k.x * k.z * v + k.y * s;
  r.m[3] = k.y * k.x * v + k.z * s, r.m[4] = c + k.y * k.y * v, r.m[5] = k.y * k.z * v - k.x * s;
  r.m[6] = k.z * k.x * v - k.y * s, r.m[7] = k.z * k.y * v + k.x * s, r.m[8] = c + k.z * k.z * v;
  return r;
}
/// The angle of a rotation, degrees, in [0, 180].
double rotation_angle_deg(const Mat3d& r);

/// A rigid motion x -> r x + t.
struct Motion {
  Mat3d r;
  Vec3d t;
};
inline Motion compose(const Motion& a, const Motion& b) { return {a.r * b.r, a.r * b.t + a.t}; }  // a o b
inline Motion rotation_about(Vec3d p, const Mat3d& r) { return {r, p - r * p}; }
inline Vec3d apply(const Motion& m, Vec3d p) { return m.r * p + m.t; }
/// The motion applied to an organ transform (columns rotated, joint moved), rounded to float.
inline Affine3f apply(const Motion& m, const Affine3f& a) {
  Affine3f o;
  o.c0 = to_float(m.r * to_double(a.c0));
  o.c1 = to_float(m.r * to_double(a.c1));
  o.c2 = to_float(m.r * to_double(a.c2));
  o.t = to_float(apply(m, to_double(a.t)));
  return o;
}

/// The resolution state of a stand: grown transforms, subtrees, the turned joints.
class Joints {
 public:
  explicit Joints(const Stand& stand);

  /// Organs [k, subtree_end(k)) are k and everything distal to it (the structure tree is
  /// depth-first in string order).
  std::uint32_t subtree_end(std::uint32_t k) const { return subtree_end_[k]; }
  /// Whether organ x is k or distal to it (turns with k).
  bool holds(std::uint32_t k, std::int32_t x) const {
    return x >= 0 && static_cast<std::uint32_t>(x) >= k && static_cast<std::uint32_t>(x) < subtree_end_[k];
  }
  const Affine3f& grown(std::uint32_t k) const { return grown_[k]; }
  /// The current joint angle of organ k, degrees (0 where it never turned).
  double angle_deg(std::uint32_t k) const;
  /// D_k: grown pose -> current pose of organ k (plant frame).
  Motion motion(std::uint32_t k) const;
  /// The local rotation that turning organ k by `turn` (a rotation in the plant frame about its
  /// current joint) would leave at its joint.
  Mat3d local_after(std::uint32_t k, const Mat3d& turn) const;
  /// The same in two steps for many turns of one organ: `frame` once, then `local_after(frame, turn)`.
  struct JointFrame {
    Mat3d parent, parent_t, local;  // the parent's rotation (D_parent), its transpose, Q_k
  };
  JointFrame joint_frame(std::uint32_t k) const;
  static Mat3d local_after(const JointFrame& f, const Mat3d& turn) { return f.parent_t * turn * f.parent * f.local; }
  /// Sets organ k's local rotation (as local_after gave it).
  void set_local(std::uint32_t k, const Mat3d& q);
  /// Writes current transforms into `stand` for the subtrees of `turned` organs, returns the ids
  /// of every organ whose transform was rewritten (sorted).
  std::vector<std::uint32_t> update(Stand& stand, const std::vector<std::uint32_t>& turned) const;
  /// Turned joints: organ ids, and how many.
  const std::vector<std::uint32_t>& turned() const { return turned_ids_; }
  std::size_t bytes() const { return bytes_for(grown_.size(), turned_ids_.size()); }
  /// The memory of the joints of `organs` organs of which `turned` have turned.
  static std::size_t bytes_for(std::size_t organs, std::size_t turned) {
    return organs * (sizeof(Affine3f) + 12) + turned * (sizeof(Mat3d) + 4);
  }

 private:
  std::vector<Affine3f> grown_;
  std::vector<std::int32_t> parent_;
  std::vector<std::uint32_t> subtree_end_;
  std::vector<std::int32_t> slot_;   // per organ: index into local_, -1 never turned
  std::vector<Mat3d> local_;
  std::vector<std::uint32_t> turned_ids_;
};

}  // namespace canopy
