#pragma once
/// The lines `--resolve-stats` prints on stderr after a resolution: where its time went
/// (ResolveResult::stats, resolution/resolve_stats.hpp).
#include "resolution/resolve_stats.hpp"

#include <string>

namespace canopy::cli {

/// Phase by phase (wall and CPU seconds, page faults), lane by lane of planning, and the runner
/// of bulk attempts; empty where the statistics were not collected.
std::string resolve_stats_text(const ResolveStats& s);

}  // namespace canopy::cli
