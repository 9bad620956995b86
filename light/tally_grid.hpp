#pragma once
/// The one loop that tallies a direction's grid, for the ray caster (light/sampler.cpp) and the
/// drawn cells (light/raster_stand.cpp): each row's cells in pairs of neighbours, as the
/// collapsed-strata estimator takes them (light/tally.hpp), rows shared out over the OpenMP
/// threads and the threads' tallies summed (whole counts: the same on any thread count). Kept out
/// of the headers other code includes, for its OpenMP pragmas.
#include "light/sampler.hpp"
#include "light/tally.hpp"

#include <cstdint>

namespace canopy::light {

/// `outcome(i, j)`: what the ray of cell (i, j) met. `rows_per_task`: rows a thread takes at once
/// (1 where a row costs much, as tracing does).
template <class OutcomeOf>
Tally tally_grid(const Grid& g, std::size_t plants, std::size_t layers, int rows_per_task,
                 const OutcomeOf& outcome) {
  Tally total(plants, layers);
  const auto ny = static_cast<std::int64_t>(g.ny);
#pragma omp parallel
  {
    Tally mine(plants, layers);
#pragma omp for schedule(dynamic, rows_per_task) nowait
    for (std::int64_t jj = 0; jj < ny; ++jj) {
      const auto j = static_cast<std::uint64_t>(jj);
      for (std::uint64_t i = 0; i < g.nx; i += 2) {
        const Outcome a = outcome(i, j), b = outcome(i + 1, j);
        mine.add(a), mine.add(b), mine.add_pair(a, b);
      }
    }
#pragma omp critical
    total += mine;
  }
  return total;
}

}  // namespace canopy::light
