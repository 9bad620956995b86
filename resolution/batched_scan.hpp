#pragma once
/// Resolution's level-by-level scan with each level's attempts run together by an
/// AttemptRunner (the device's, on CUDA): for every candidate of a level, all its axes at the
/// level's angle at once against the organs it met, then (a strict search) the axes that cleared
/// them against its neighbours; the first axis in order that clears both is the one
/// TurnSearch::scan_level finds, and the bisection of TurnSearch::refine runs as steps over all
/// found candidates, in the same calls as the next level's scan (the two sets of candidates are
/// apart). An attempt's answer is a conjunction over its pairs, the same whoever tests them in
/// whatever order and beside whichever other attempts, so the turns are the candidate-by-candidate
/// search's.
///
/// The host keeps what is cheap or branchy: the joint-limit checks, the neighbour gathering (for
/// the candidates whose axes cleared the organs met, as the host search gathers them) and the
/// picks; the runner does the box and triangle tests, which are nearly all the work.
#include "resolution/attempt_batch.hpp"
#include "resolution/resolve_stats.hpp"
#include "resolution/turn_search.hpp"

#include <span>
#include <vector>

namespace canopy {

class BatchedScan {
 public:
  /// Through lane `lane` of the runner (resolution/attempt_batch.hpp), writing into `tables` where
  /// given (the caller keeps them from round to round, so that their memory, hundreds of
  /// megabytes at 10,000 plants, is faulted in once) or into tables of its own.
  BatchedScan(const TurnSearch& search, AttemptRunner& runner, int threads, std::size_t lane = 0,
              AttemptTables* tables = nullptr)
      : search_(search), runner_(runner), threads_(threads), lane_(lane),
        tables_(tables ? *tables : own_tables_) {}
  BatchedScan(const BatchedScan&) = delete;
  BatchedScan& operator=(const BatchedScan&) = delete;
  /// Adds where the host's time went (PlanLaneStats: scan_s to gathers) to `to`.
  void add_stats(PlanLaneStats& to) const;
  /// A new batch of contacts: the tables start empty (candidates of the last batch are gone).
  void clear();
  /// TurnSearch::scan_level(c, level) for each candidate of `scan`, and TurnSearch::refine(c)
  /// for each of `refine` (each has found an axis, at an earlier level), in the same calls to the
  /// runner: the refinement of one level's finds rides along with the next level's scan, which
  /// halves the round trips a level makes. The refined turns, one per candidate of `refine`.
  std::vector<Turn> scan_and_refine(std::span<TurnSearch::Candidate* const> scan, int level,
                                    std::span<TurnSearch::Candidate* const> refine);

 private:
  /// Puts each candidate's moving organs, axes and pairs with the organs met in the tables
  /// (those not there yet), and for `near` its neighbours' pairs where they were gathered anew.
  void add_tables(std::span<TurnSearch::Candidate* const> cands, bool near);
  /// Up to 32 of a candidate's axes: bit i of `mask` is axis first + i.
  struct AxisSet {
    std::uint32_t first = 0, mask = 0;
  };
  /// Per candidate j, the axes of want[j] that clear every pair it must clear at angle deg[j]
  /// (a mask over the same axes). A strict candidate's neighbours are gathered here when some
  /// axis clears the organs met and they do not cover deg[j] yet.
  std::vector<std::uint32_t> clear_axes(std::span<TurnSearch::Candidate* const> cands,
                                        std::span<const double> deg, std::span<const AxisSet> want);

  const TurnSearch& search_;
  AttemptRunner& runner_;
  int threads_;
  std::size_t lane_;
  AttemptTables own_tables_;
  AttemptTables& tables_;
  struct Times {
    double scan = 0, limits = 0, tables = 0, gather = 0, runner = 0;
    std::size_t gathers = 0;
  } times_;
};

}  // namespace canopy
