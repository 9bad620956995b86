#include "distributed/region.hpp"

#include <algorithm>
#include <stdexcept>

namespace canopy {
namespace {

/// Appends plant p of `from` to `to`, renumbering its organs, leaves and grammar.
void append_plant(Stand& to, const Stand& from, std::size_t p) {
  PlantRecord pr = from.plants[p];
  const std::string& grammar = from.grammars[static_cast<std::size_t>(pr.grammar)];
  const auto g = std::find(to.grammars.begin(), to.grammars.end(), grammar);
  pr.grammar = static_cast<int>(g - to.grammars.begin());
  if (g == to.grammars.end()) to.grammars.push_back(grammar);
  const auto organ_shift =
      static_cast<std::int64_t>(to.organs.size()) - static_cast<std::int64_t>(pr.first_organ);
  const std::uint32_t leaves =
      to.plants.empty() ? 0 : to.plants.back().first_leaf + to.plants.back().leaf_count;
  const auto leaf_shift = static_cast<std::int64_t>(leaves) - static_cast<std::int64_t>(pr.first_leaf);
  const auto plant = static_cast<std::int32_t>(to.plants.size());
  for (std::uint32_t k = pr.first_organ; k < pr.first_organ + pr.organ_count; ++k) {
    OrganRecord r = from.organs[k];
    r.plant = plant;
    if (r.parent >= 0) r.parent = static_cast<std::int32_t>(r.parent + organ_shift);
    if (r.leaf >= 0) r.leaf = static_cast<std::int32_t>(r.leaf + leaf_shift);
    to.organs.push_back(r);
    to.transforms.push_back(from.transforms[k]);
    to.params.push_back(from.params[k]);
    to.joint_limit_deg.push_back(from.joint_limit_deg[k]);
  }
  pr.first_organ = static_cast<std::uint32_t>(pr.first_organ + organ_shift);
  pr.first_leaf = static_cast<std::uint32_t>(pr.first_leaf + leaf_shift);
  to.plants.push_back(pr);
}

}  // namespace

Stand merge_region(const Stand& own, const std::vector<std::uint32_t>& own_ids, const Stand& halo,
                   const std::vector<std::uint32_t>& halo_ids) {
  if (own.plant_count() != own_ids.size() || halo.plant_count() != halo_ids.size())
    throw std::logic_error("merge_region: a stand and its ids differ in length");
  Stand out;
  out.organs.reserve(own.organ_count() + halo.organ_count());
  out.transforms.reserve(own.organ_count() + halo.organ_count());
  out.params.reserve(own.organ_count() + halo.organ_count());
  out.joint_limit_deg.reserve(own.organ_count() + halo.organ_count());
  out.plants.reserve(own_ids.size() + halo_ids.size());
  std::size_t i = 0, j = 0;
  while (i < own_ids.size() || j < halo_ids.size()) {
    if (j == halo_ids.size() || (i < own_ids.size() && own_ids[i] < halo_ids[j])) append_plant(out, own, i++);
    else append_plant(out, halo, j++);
  }
  return out;
}

}  // namespace canopy
