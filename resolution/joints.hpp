#pragma once
/// Joints for resolution: an organ turns about its joint (its attachment point, the translation
/// of its grown transform) and carries its whole subtree of the structure tree with it. Each
/// turned organ k holds a local rotation Q_k about its grown joint j_k, expressed in its parent's
/// grown frame, so the rigid motion that takes grown poses to current ones is
///   D_k = D_parent(k) o J_k,   J_k = rotation Q_k about j_k  (identity where k never turned),
/// and the current transform is T_k = D_k o G_k (G the grown transform). The joint angle |Q_k|
/// is what the joint limit bounds (docs/design.md "Organs": at most joint_limit degrees from the
/// grown orientation). Organs under no turned joint keep their grown transform bit for bit.
#include "geometry/first_touch.hpp"
#include "geometry/motion.hpp"
#include "geometry/stand.hpp"

#include <cstdint>
#include <vector>

namespace canopy {

/// Rodrigues' formula: rotation by `angle` radians about the unit `axis`.
Mat3d axis_angle(Vec3d axis, double angle);
/// The angle of a rotation, degrees, in [0, 180].
double rotation_angle_deg(const Mat3d& r);

/// The resolution state of a stand: grown transforms, subtrees, the turned joints.
class Joints {
 public:
  /// From the stand as grown (its transforms kept as the grown ones), on `threads` threads.
  explicit Joints(const Stand& stand, int threads = 1);

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
  static Mat3d local_after(const JointFrame& f, const Mat3d& turn) {
    return f.parent_t * turn * f.parent * f.local;
  }
  /// Sets organ k's local rotation (as local_after gave it).
  void set_local(std::uint32_t k, const Mat3d& q);
  /// Writes current transforms into `stand` for the subtrees of `turned` organs (on `threads`
  /// threads, 0: all), returns the ids of every organ whose transform was rewritten (sorted).
  std::vector<std::uint32_t> update(Stand& stand, const std::vector<std::uint32_t>& turned,
                                    int threads = 0) const;
  /// Turned joints: organ ids, and how many.
  const std::vector<std::uint32_t>& turned() const { return turned_ids_; }
  std::size_t bytes() const { return bytes_for(grown_.size(), turned_ids_.size()); }
  /// The memory of the joints of `organs` organs of which `turned` have turned.
  static std::size_t bytes_for(std::size_t organs, std::size_t turned) {
    return organs * (sizeof(Affine3f) + 12) + turned * (sizeof(Mat3d) + 4);
  }

 private:
  std::vector<Affine3f, FirstTouchAllocator<Affine3f>> grown_;  // written by the threads that use it
  // Per organ, written in full on all threads by the constructor (10,000 plants: 35 MB that one
  // thread used to zero first).
  std::vector<std::int32_t, FirstTouchAllocator<std::int32_t>> parent_;
  std::vector<std::uint32_t, FirstTouchAllocator<std::uint32_t>> subtree_end_;
  std::vector<std::int32_t, FirstTouchAllocator<std::int32_t>> slot_;  // index into local_, -1 never turned
  std::vector<Mat3d> local_;
  std::vector<std::uint32_t> turned_ids_;
};

}  // namespace canopy
