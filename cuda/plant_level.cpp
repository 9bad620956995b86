#include "cuda/plant_level.hpp"

#include "collision/memory_budget.hpp"
#include "cuda/device_lists.hpp"
#include "cuda/grid_kernels.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace canopy::cuda {

std::vector<std::uint64_t> PlantLevel::work(const StandOnDevice& dev, const DetectRequest& req, bool tight,
                                            KeyOps& keys, DeviceBuffer<Counters>& counters, EventTimer& timer,
                                            std::optional<LevelCount>& count, DeviceBuffer<WorkItem>& work) {
  const std::uint32_t np = dev.plants();
  // Cells at least twice the largest radius, and few enough that coordinates fit 31 bits.
  const double cell = std::max({2.0 * static_cast<double>(dev.max_radius()), 1e-3, dev.span() / 1e9});
  if (cell != sorted_cell_) {
    cells_.fit(np, tight), members_.fit(np, tight), sorted_cells_.fit(np, tight),
        sorted_members_.fit(np, tight);
    timer.start();
    launch_plant_cells(dev.view().origins, np, dev.x0(), dev.y0(), cell, cells_.get(), members_.get());
    keys.sort_pairs(cells_.get(), sorted_cells_.get(), members_.get(), sorted_members_.get(), np);
    timer.stop();
    sorted_cell_ = cell;
  }
  const std::uint8_t* active = nullptr;
  if (req.active_plants) {
    if (req.active_plants->size() != np)
      throw std::invalid_argument("detect: active_plants needs one flag per plant");
    active_.upload(*req.active_plants);
    active = active_.get();
  }
  const GridView g{dev.view().plants,
                   dev.view().origins,
                   sorted_cells_.get(),
                   sorted_members_.get(),
                   np,
                   dev.x0(),
                   dev.y0(),
                   cell,
                   dev.self(),
                   active};
  Counters host{};
  const std::size_t nw = collect(
      pair_keys_, counters, host, 8 * std::size_t{np} + 64, kMaxItems, tight, timer,
      [&](std::uint64_t* o, unsigned long long cap) { launch_plant_pairs(g, o, cap, counters.get()); });
  // The host holds the list too, and what detection and resolution make of it (collision/memory_budget.hpp).
  if (const std::size_t budget = memory_budget(req.memory_limit);
      budget && !req.active_plants && host.between > most_plant_pairs(budget))
    refuse_plant_pairs(most_plant_pairs(budget), budget);
  if (nw > kMaxItems) throw CudaError(fmt::format("{} plant pairs: more than one launch can list", nw));
  count = LevelCount{static_cast<std::size_t>(host.between), static_cast<std::size_t>(host.within)};
  work_keys_.fit(nw, tight), work.fit(nw, tight);
  timer.start();
  keys.sort(pair_keys_.get(), work_keys_.get(), nw);
  launch_work_items(dev.view(), work_keys_.get(), static_cast<std::uint32_t>(nw), work.get());
  timer.stop();
  std::vector<std::uint64_t> out;
  append_download(out, work_keys_.get(), nw, staged_keys_);
  if (tight) {  // under a budget, only the work list stays for the stages
    for (auto* b : {&cells_, &sorted_cells_, &pair_keys_, &work_keys_}) b->resize(0);
    members_.resize(0), sorted_members_.resize(0), keys.release(), sorted_cell_ = 0;
  }
  return out;
}

}  // namespace canopy::cuda
