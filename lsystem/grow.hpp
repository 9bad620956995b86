#pragma once
/// Grows a stand: for each placed plant, derive its string from its own seed, interpret it, run
/// the turtle, and place its organs (rotation about +Z; origin kept apart in double).
#include "geometry/layout.hpp"
#include "geometry/stand.hpp"
#include "lsystem/derive.hpp"
#include "lsystem/grammar.hpp"

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace canopy {

struct GrowRequest {
  std::string grammar;                 // the stand's grammar file
  std::vector<PlantPlacement> plants;  // a placement may name another grammar (positions files)
  std::string relative_to;             // folder for relative grammar paths in placements
  std::string positions_file;          // the file the placements were read from, for messages
  LoadOptions load;                    // --set overrides, applied to every grammar
  std::optional<int> steps;            // overrides every grammar's steps (a placement's own wins)
  int lod = 2;
  std::size_t max_modules = kDefaultMaxModules;
  int threads = 0;  // 0: all cores
  /// Refuse before growing when the stand would need more than this many bytes (0: the
  /// machine's available memory).
  std::size_t memory_limit = 0;
};

struct GrowTimings {
  double derive_s = 0, turtle_s = 0, place_s = 0;
};

/// The grammar file a placement names (`name`, relative to the positions file), or the stand's
/// where it names none.
std::string grammar_path(const GrowRequest& req, const std::string& name);

/// Throws GrammarError for grammar problems (an organ's parameter out of range located at the
/// expression that wrote it), std::invalid_argument for a level of detail outside 1..kMaxLod,
/// steps outside 0..kMaxSteps, a thread count past max_threads() (or OMP_NUM_THREADS past it when
/// none is given), and naming the plant for a position or rotation that is not finite or a position past
/// kMaxPlantCoordinate,
/// std::runtime_error for a stand too large for memory (said before growing it). A failing plant's
/// exception is thrown as it was, the first in plant order.
Stand grow_stand(const GrowRequest& request, GrowTimings* timings = nullptr);

/// Grows the first plant of `request` alone and throws, before anything large is allocated, when
/// `plants` plants like it would not fit in the memory limit (a stand too large for memory).
void check_stand_fits(const GrowRequest& request, std::size_t plants);

/// Bytes of memory this machine has available (MemAvailable), or 0 when unknown.
std::size_t available_memory();

}  // namespace canopy
