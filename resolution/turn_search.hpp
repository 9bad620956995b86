#pragma once
/// The turn of an organ (with everything distal to it) about its joint that separates it from
/// the organs it met. Candidates (several movers, each on several axes) are scanned together in
/// order of cost, cost = angle x the mover's kind weight (ResolveConfig::kind_weight), so the
/// cheapest separating turn is found first: a leaflet turns unless its rachis or petiole can do
/// it for a fraction of the angle. A petiole, rachis or peduncle segment may be asked for as much
/// as a turn spread over its chain could take (Candidate::chain_deg). Axes: the one that swings
/// the contact organs straight away
/// from what they met, then a fan across the mover's width-normal plane and its own long axis
/// both ways. The angle found is refined by bisection to ResolveConfig::angle_tolerance_deg and
/// never takes the joint past its limit.
///
/// Separation means the exact test with the resolution clearance finds nothing (or, at the
/// organ level, the OBBs grown by the clearance no longer overlap). A strict search also keeps
/// the turned organs clear of every organ within their reach that was clear before the turn, so
/// a turn never trades one contact for another; where no strict turn exists, a relaxed search
/// asks only for the organs met.
///
/// Speed without changing an answer (each attempt's answer is a conjunction over its pairs, so
/// only the order of work changes): an attempt first retests the pairs that blocked the last few
/// attempts, and in each organ pair the triangle pairs that touched last (Witness); a strict
/// candidate's neighbours are gathered only when an attempt first clears every organ met (most
/// candidates of a contact are never picked and fail before that); the joint's rotation is made
/// only near its limit (rotation angles obey the triangle inequality) or for a separating turn.
#include "resolution/contact_graph.hpp"
#include "collision/contacts.hpp"
#include "collision/exact.hpp"
#include "resolution/joints.hpp"
#include "resolution/neighbourhood.hpp"
#include "resolution/resolve_policy.hpp"
#include "geometry/obb.hpp"

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace canopy {

inline constexpr std::uint32_t kNoPair = ~0u;

struct Turn {
  std::uint32_t organ = 0;
  Mat3d local;           // the joint's local rotation after the turn (Joints::set_local)
  double angle_deg = 0;  // this round's turn
};

/// Organ pairs (x, y) to separate: x the organ of the contact the mover carries, y the other.
using MetPairs = std::vector<std::pair<std::int32_t, std::int32_t>>;

struct TurnSearch {
  const Stand& stand;
  const Joints& joints;
  PrototypeLibrary& lib;
  const ResolveConfig& config;
  KindMask collide;
  const Neighbourhood& near;
  std::span<const Obb> boxes;    // every organ's current OBB (no clearance), kept up to date by the caller
  const ContactGraph& touching;  // contacts at the start of the round
  float clearance = 0;           // separation from the organs met (the larger of both clearances)
  float detect_clearance = 0;    // what detection counts as a contact: neighbours must stay this far
  /// Per organ, where given: a chain mover whose turn past its own limit no spread could take
  /// (resolution/bend_spread.hpp); it is searched within its own limit from then on.
  const std::vector<std::uint8_t>* unbendable = nullptr;

  /// Organ pairs (moving organ, kept organ) that some turn about the joint could bring together
  /// (the sphere of x sweeps a shell about the joint): keep indices for moving[i] in
  /// y[first[i], first[i+1]).
  struct PairSet {
    std::vector<std::uint32_t> first, y;
    /// The triangles that touched last: one per pair for the organs met (they touched when the
    /// round began); for the neighbours (`sparse`), which mostly never touch, only those of
    /// pairs that touched since, `slot[p]` naming pair p's (kNoPair: none). The host's attempts
    /// make the neighbours' lists when they first need them (host_state); a batched search
    /// keeps its own on the runner's side.
    std::vector<Witness> witness;
    std::vector<std::uint32_t> slot;
    bool sparse = false;
    void clear() { first.clear(), y.clear(), witness.clear(), slot.clear(); }
    /// Pair p's witness, or null where it has none.
    Witness* find(std::uint32_t p) {
      if (!sparse) return p < witness.size() ? &witness[p] : nullptr;
      return p < slot.size() && slot[p] != kNoPair ? &witness[slot[p]] : nullptr;
    }
    const Witness* find(std::uint32_t p) const { return const_cast<PairSet*>(this)->find(p); }
    /// Pair p's witness, made empty where a sparse set has none (a reference valid until the
    /// next one is made).
    Witness& make(std::uint32_t p) {
      if (Witness* w = find(p)) return *w;
      slot[p] = static_cast<std::uint32_t>(witness.size());
      return witness.emplace_back();
    }
  };
  /// One mover's search state: what moves, what it must clear, its axes and reach.
  struct Candidate {
    std::uint32_t mover = 0;
    Vec3d joint;
    Joints::JointFrame frame;
    double weight = 1, reach_deg = 0, angle_now_deg = 0;
    /// How far a turn of a petiole, rachis or peduncle segment may go when it is spread over its
    /// chain (resolution/bend_chain.hpp): turns up to this pass the joint limit whatever the
    /// mover's own joint says (the plan spreads them, resolution/bend_spread.hpp); 0: no chain.
    double chain_deg = 0;
    std::vector<std::int32_t> moving,
        keep;  // keep: the organs met first (met_count of them), then neighbours
    std::size_t met_count = 0;
    std::vector<Vec3f> keep_off;  // per keep organ: the offset into the mover's plant frame
    std::vector<Vec3d> axes;
    /// Pairs with the organs met, and (a strict search) with the neighbours to keep clear. The
    /// neighbours are gathered when an attempt first clears every organ met: most candidates
    /// never get that far before another candidate of their contacts wins.
    PairSet met_pairs, near_pairs;
    bool strict = false;
    /// The largest turn (degrees) the neighbours gathered cover (-1: none gathered yet). They
    /// are gathered for a few levels beyond the attempt that first needs them, not for the whole
    /// reach: a small turn sweeps the subtree through a small region (the chord bound), and most
    /// searches end within a level or two; a larger attempt gathers again for twice the turn.
    double near_deg = -1;
    /// The pairs (set: 0 met, 1 near; index into `moving`; pair index) that blocked the last few
    /// failed attempts, tested first: the scan swings about several axes, each blocked by a pair
    /// of its own.
    struct Blocker {
      std::uint32_t set = 0, organ = 0, pair = kNoPair;
    };
    static constexpr int kBlockers = 4;
    Blocker blocker[kBlockers];
    int latest_blocker = 0;
    /// Per axis: the pair and the triangles (by organ order, as Witness keeps them) that blocked
    /// the last attempt about it, tested first when the scan comes back to the axis at the next
    /// level or the bisection tries it again: the same triangles usually still touch a few
    /// degrees further on, and the ring of recent blockers is shared by all the axes.
    struct AxisBlock {
      Blocker by;
      std::uint16_t tri_a = Witness::kNone, tri_b = Witness::kNone;
    };
    std::vector<AxisBlock> axis_block;
    // Scan state: angles up to lo tried and failed; found_axis >= 0 when `hi` separates.
    double lo = 0, hi = 0;
    int found_axis = -1;
    Mat3d local;
    /// Where a batched scan (resolution/batched_scan.hpp) put this candidate in its tables:
    /// slots of its moving organs and axes, its pairs with the organs met and with the
    /// neighbours gathered for `near_deg` (kNoPair: not there yet).
    struct Tables {
      std::uint32_t moving = kNoPair, axes = 0, met_first = 0, met_end = 0, near_first = 0, near_end = 0;
      double near_deg = -1;
    } tables;
    double trig_deg = -1, trig_cos = 1, trig_sin = 0;  // the last angle turned by, its cosine and sine
    bool exhausted() const { return found_axis < 0 && lo >= reach_deg; }
    /// Neither found nor exhausted: the scan goes on to the next level.
    bool searching() const { return found_axis < 0 && lo < reach_deg; }
    /// Back to a new candidate's state, keeping the memory of its lists: resolution plans tens
    /// of thousands of candidates per batch, and making and letting go of their lists cost it
    /// as much as a tenth of its time on 16 threads.
    void recycle();
  };
  Candidate prepare(std::uint32_t mover, const MetPairs& met, bool strict) const;
  /// The same, into a candidate whose lists are reused (Candidate::recycle).
  void prepare(Candidate& c, std::uint32_t mover, const MetPairs& met, bool strict) const;
  /// Tries the candidate's axes at cost level `level` (angle = level x step / weight, capped at
  /// its reach); true when one separates (then found_axis, hi and local are set).
  bool scan_level(Candidate& c, int level, ExactScratch& scratch) const;
  /// The found turn refined by bisection between the last failed and the found angle.
  Turn refine(Candidate& c, ExactScratch& scratch) const;
  /// Whether turning by `deg` about axis `a` keeps the joint in its limit and clears the list;
  /// `local` gets the joint's rotation.
  /// `axis`: the index of `a` in c.axes, so that the attempt starts from what blocked that axis
  /// last (-1: an axis of the caller's own).
  bool attempt(Candidate& c, const Vec3d& a, double deg, Mat3d& local, ExactScratch& scratch,
               int axis = -1) const;
  /// Whether turning by `deg` about `a` keeps the joint within its limit (attempt's check).
  bool within_limit(Candidate& c, const Vec3d& a, double deg) const;
  /// The joint's local rotation after turning by `deg` about `a` (what attempt gives `local`).
  Mat3d local_after(Candidate& c, const Vec3d& a, double deg) const;
  /// A strict search's neighbours for turns up to at least `deg`: every organ that a turn of
  /// the subtree about the joint by that much could bring within the clearance and that is
  /// clear now (appended to keep, replacing those gathered before), and their pairs.
  void gather_neighbours(Candidate& c, double deg) const;

 private:
  /// The turn by `deg` about `a` (its cosine and sine kept for the next attempt at that angle).
  Mat3d rotation(Candidate& c, const Vec3d& a, double deg) const;
  /// Whether a turn by `deg` may take the joint past its limit (only then is it checked).
  bool near_limit(const Candidate& c, double deg) const;
  /// keep_off for keep[from, end).
  void keep_offsets(Candidate& c, std::size_t from) const;
  /// What only the host's attempts read, made for what is new since they last looked: the
  /// neighbour pairs' witnesses.
  void host_state(Candidate& c) const;
  /// The pairs of moving organs with keep[from, to) that a turn by at most `max_deg` could bring
  /// together.
  void link_pairs(const Candidate& c, std::size_t from, std::size_t to, double max_deg, PairSet& out) const;
};

}  // namespace canopy
