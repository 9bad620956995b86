#include "collision/attempt_runner_host.hpp"

#include "collision/exact.hpp"

#include <omp.h>

namespace canopy {

std::vector<std::uint32_t> HostAttemptRunner::touching(const AttemptTables& t, std::span<const AttemptGroup> groups,
                                                       const AttemptSettings& settings) {
  std::vector<std::uint32_t> out(groups.size(), 0);
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
          const MovingEntry& x = t.moving[t.pairs[p].moving];
          const KeepEntry& y = t.keep[t.pairs[p].keep];
          if (!turned_boxes_meet(x, y, turn, settings.clearance)) continue;
          bool touches = !settings.exact;
          if (!touches) {
            const Affine3f tx = apply(turn, x.transform);
            touches = x.organ < y.organ ? organs_touch_at(stand_, lib_, x.organ, tx, y.organ, y.transform, y.gap, scratch)
                                        : organs_touch_at(stand_, lib_, y.organ, y.transform, x.organ, tx, y.gap, scratch);
          }
          if (touches) {
            out[g] |= 1u << i;
            break;
          }
        }
      }
    }
  }
  return out;
}

}  // namespace canopy
