#pragma once
/// `--backend auto` (docs/design.md "Command line"): the preferred backend whole, every member
/// forwarded (its runner of resolution's bulk attempts too, so `auto` on a GPU plans on the
/// device exactly as `--backend cuda` does), and from its first BackendFailure on a fallback
/// backend made then (the CPU's), said once on stderr. The answers are the same either way: both
/// backends find the same contacts and a runner's answers equal the host's, so a failure half-way
/// through a resolution changes where the work runs, never the files. The rest of a round whose
/// device attempts failed is answered on the host (HostAttemptRunner), later rounds by the
/// fallback backend (the CPU's host search).
///
/// DetectionBackend, AttemptSource and AttemptRunner have no member with a default: a member
/// added to any of them fails to compile here until this wrapper says what it does with it.
#include "resolution/attempt_source.hpp"
#include "collision/backend.hpp"

#include <functional>
#include <memory>

namespace canopy {

using BackendMaker = std::function<std::unique_ptr<DetectionBackend>()>;

std::unique_ptr<DetectionBackend> make_auto_backend(std::unique_ptr<DetectionBackend> preferred,
                                                    BackendMaker fallback);

}  // namespace canopy
