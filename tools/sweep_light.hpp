#pragma once
/// The light columns of a sweep's rows: ground cover, the direct beam at the sweep's sun, the
/// diffuse sky, STAR and the mean leaflet inclination, periodic over the stand's lattice, of the
/// stand as grown ("before") and as resolved ("after").
#include "geometry/layout.hpp"
#include "geometry/stand.hpp"
#include "tools/sweep_run.hpp"

#include <string>

namespace canopy::cli {

/// Throws std::invalid_argument when the sweep's light options are out of range (before any run).
void check_sweep_light(const SweepOptions& o);

/// Fills ground_cover_WHEN, direct_WHEN, diffuse_WHEN, star_WHEN, mean_inclination_WHEN and
/// light_se_WHEN (the largest standard error of the four fractions) of `row`; returns seconds.
double light_columns(const Stand& stand, const RowLayout& layout, const SweepOptions& o,
                     const std::string& when, RunRow& row);

}  // namespace canopy::cli
