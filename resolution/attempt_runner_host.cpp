#include "resolution/attempt_runner_host.hpp"

#include "collision/exact.hpp"

#include <omp.h>

namespace canopy {

std::vector<std::uint32_t> HostAttemptRunner::touching(std::size_t, const AttemptTables& t,
                                                       std::span<const AttemptGroup> groups,
                                                       const AttemptSettings& settings) {
  std::vector<std::uint32_t> out(groups.size(), 0);
  calls_.fetch_add(1, std::memory_order_relaxed);
  groups_.fetch_add(groups.size(), std::memory_order_relaxed);
#pragma omp parallel num_threads(threads_)
  {
    ExactScratch scratch;
#pragma omp for schedule(dynamic, 16)
    for (std::size_t g = 0; g < groups.size(); ++g) {
      const AttemptGroup& group = groups[g];
      for (std::uint32_t i = 0; i < 32; ++i) {
        if (!(group.axis_mask >> i & 1u)) continue;
        const Motion turn = group_turn(group, t.axes[group.axis_first + i]);
        for (std::uint32_t p = group.pair_first; p < group.pair_end; ++p) {
          const std::int32_t x = t.moving[t.pairs[p].moving];
          const KeepEntry& y = t.keep[t.pairs[p].keep];
          const auto xi = static_cast<std::size_t>(x), yi = static_cast<std::size_t>(y.organ);
          if (!turned_boxes_meet(boxes_[xi], boxes_[yi], y, turn, settings.clearance)) continue;
          // At the organ level the boxes decide; otherwise the exact test at the turned pose.
          if (!settings.exact || organs_touch_either(*stand_, lib_, x, apply(turn, stand_->transforms[xi]),
                                                     y.organ, stand_->transforms[yi], y.gap, scratch)) {
            out[g] |= 1u << i;
            break;
          }
        }
      }
    }
  }
  return out;
}

AttemptStats HostAttemptRunner::take_statistics() {
  AttemptStats s;
  s.hardware = hardware();
  s.calls = calls_.exchange(0), s.groups = groups_.exchange(0);
  return s;
}

}  // namespace canopy
