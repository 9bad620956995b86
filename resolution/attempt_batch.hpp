#pragma once
/// Turn-search attempts in bulk (resolution's planning, resolution/batched_scan.hpp): a level's
/// attempts of many candidates, each about several axes, handed over at once to a runner that
/// answers, per attempt, whether some pair it must clear touches. The records are plain (both
/// backends read them) and the per-pair predicate is one CANOPY_HD function plus the exact organ
/// test, so a runner on the device gives the host's answers bit for bit.
///
/// Tables grow append-only through a batch of contacts: a candidate's moving organs, the organs
/// it keeps clear (the met ones once, its neighbours again each time it gathers them) and its
/// pairs go in once, and every level's groups point into them.
#include "geometry/first_touch.hpp"
#include "geometry/hd.hpp"
#include "geometry/motion.hpp"
#include "geometry/obb.hpp"
#include "geometry/stand.hpp"
#include "geometry/vec.hpp"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace canopy {

/// An organ a candidate must keep clear: the clearance it must keep and the offset of its plant
/// frame in the mover's. Its transform and OBB are the stand's (AttemptRunner::update_organs).
struct KeepEntry {
  std::int32_t organ = 0;
  float gap = 0;
  Vec3f offset;
};

/// A pair to clear: slots into the moving table (organ ids) and the keep table.
struct PairEntry {
  std::uint32_t moving = 0, keep = 0;
};

/// One candidate at one angle about up to 32 of its axes: pairs [pair_first, pair_end) checked
/// for the axes in `axis_mask` (bit i: axes[axis_first + i]).
struct AttemptGroup {
  Vec3d joint;
  double cos = 1, sin = 0;  // of the angle (the host's std::cos and std::sin)
  std::uint32_t axis_first = 0, pair_first = 0, pair_end = 0, axis_mask = 0;
};

/// Whether the boxes of a pair meet when the moving organ (OBB `x`, no clearance) turns by
/// `turn`: its box carried and grown by the search clearance against the kept organ's box `y`
/// grown by its gap (TurnSearch::attempt's first test, made the same way).
CANOPY_HD inline bool turned_boxes_meet(const Obb& x, const Obb& y, const KeepEntry& keep, const Motion& turn,
                                        float clearance) {
  return obb_overlap(carried_box(x, turn, clearance), grown(y, keep.gap), keep.offset);
}

/// The rotation of group g about its axis `a` as the host's attempt makes it.
CANOPY_HD inline Motion group_turn(const AttemptGroup& g, Vec3d axis) {
  return rotation_about(g.joint, axis_angle(axis, g.cos, g.sin));
}

/// No triangle pair known to touch (AttemptTables::witness).
inline constexpr std::uint32_t kNoWitness = ~0u;

/// A batch's tables on the host; a runner copies what was appended since it last looked. Grown
/// without writing the new entries (the batched scan writes each once, on all threads: at 10,000
/// plants tens of millions of entries a round).
struct AttemptTables {
  template <typename T>
  using Table = std::vector<T, FirstTouchAllocator<T>>;
  Table<std::int32_t> moving;
  Table<KeepEntry> keep;
  Table<PairEntry> pairs;
  /// Per pair: the triangles that touched when the round began (of the lower organ << 16 | of
  /// the higher, as Witness keeps them), or kNoWitness. A runner may test them first and keep
  /// them up to date on its side: a touch there is a touch of the organs, so only the order of
  /// the work changes, never an answer.
  Table<std::uint32_t> witness;
  Table<Vec3d> axes;
  void clear() { moving.clear(), keep.clear(), pairs.clear(), witness.clear(), axes.clear(); }
};

/// What a runner needs besides the tables.
struct AttemptSettings {
  float clearance = 0;  // the search clearance the moving boxes grow by
  bool exact = true;    // false: the organ level (overlapping boxes touch)
};

/// What a runner did (ResolveRequest::statistics): its calls, the attempt groups and the box and
/// exact tests they made, the bytes it sent, and the host's seconds in its calls (summed over
/// lanes, which overlap): handing over the uploads, until the box tests' count was back, until the
/// answers were. A runner counts what its hardware lets it count; the host's counts calls and
/// groups.
struct AttemptStats {
  std::string hardware;   // AttemptRunner::hardware()
  std::size_t lanes = 0;  // lanes that worked
  std::uint64_t calls = 0, groups = 0, box_tests = 0, witness_hits = 0, exact_tests = 0, exact_touches = 0,
                uploaded_bytes = 0;
  double call_s = 0, upload_s = 0, box_s = 0, exact_s = 0;
  /// The device's own clock, where the runner kept it: from the first call's kernels to the
  /// last's, how long some lane's kernels were queued or running, and the calls' spans summed.
  bool timeline = false;
  double kernels_span_s = 0, kernels_busy_s = 0, kernels_summed_s = 0;
  std::string no_timeline;  // why the timeline could not be read, where it could not
};

class AttemptRunner {
 public:
  virtual ~AttemptRunner() = default;
  /// The organs' transforms and OBBs (no clearance) as they stand before a round's planning:
  /// `changed` lists the organs whose pose changed since the last call (ignored with `all`,
  /// which the first call of a resolution sets). `boxes` stays alive and unchanged until the
  /// next call.
  virtual void update_organs(const Stand& stand, std::span<const Obb> boxes,
                             std::span<const std::uint32_t> changed, bool all) = 0;
  /// How many batches the runner can answer for at once, each on a lane of its own (its tables
  /// and, on the device, its own stream): one lane's host work then overlaps another's device
  /// work. A lane's calls come from one thread at a time, different lanes' from different
  /// threads; update_organs is never called while lanes work.
  virtual std::size_t lanes() const = 0;
  /// Where the attempts run, as the report says it ("device", "host"): pure, like every member,
  /// so a runner that wraps another says what it does with each.
  virtual std::string hardware() const = 0;
  /// A new batch on `lane`: its tables start empty.
  virtual void clear(std::size_t lane) = 0;
  /// Per group, bit i set where a pair touches when turned about axis i of the group's mask
  /// (the lane's tables as they stand now; entries appended since its last call are new).
  virtual std::vector<std::uint32_t> touching(std::size_t lane, const AttemptTables& tables,
                                              std::span<const AttemptGroup> groups,
                                              const AttemptSettings& settings) = 0;
  /// From now on, whether to keep what only the statistics need (on the device: an event pair
  /// around every kernel and the exact tests' touches); off until asked. Never called while
  /// lanes work.
  virtual void keep_statistics(bool on) = 0;
  /// What the runner did since the last call (since it was made, at the first); its counts start
  /// again from zero. Never called while lanes work.
  virtual AttemptStats take_statistics() = 0;
};

}  // namespace canopy
