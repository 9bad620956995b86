#include "resolution/contact_graph.hpp"

namespace canopy {

void ContactGraph::build(std::size_t organs, const std::vector<Contact>& contacts) {
  first.assign(organs + 1, 0);
  witness.clear();  // found again for this list by find_witnesses, if asked
  for (const Contact& c : contacts)
    ++first[static_cast<std::size_t>(c.organ_a) + 1], ++first[static_cast<std::size_t>(c.organ_b) + 1];
  for (std::size_t i = 0; i < organs; ++i) first[i + 1] += first[i];
  with.resize(first[organs]);
  // first[x] serves as x's cursor (it ends at first[x + 1]), then moves back by one slot.
  for (const Contact& c : contacts) {
    with[first[static_cast<std::size_t>(c.organ_a)]++] = c.organ_b;
    with[first[static_cast<std::size_t>(c.organ_b)]++] = c.organ_a;
  }
  for (std::size_t i = organs; i > 0; --i) first[i] = first[i - 1];
  first[0] = 0;
}

void ContactGraph::find_witnesses(const Stand& s, PrototypeLibrary& lib, float clearance, int threads) {
  witness.assign(with.size(), Witness{});
  const std::size_t organs = first.size() - 1;
#pragma omp parallel num_threads(threads)
  {
    ExactScratch scratch;
#pragma omp for schedule(dynamic, 256)
    for (std::size_t x = 0; x < organs; ++x)
      for (std::uint32_t e = first[x]; e < first[x + 1]; ++e) {
        const std::int32_t y = with[e];
        if (static_cast<std::int32_t>(x) > y) continue;  // each pair once, by its lower organ
        Witness w;
        organs_touch_at(s, lib, static_cast<std::int32_t>(x), s.transforms[x], y,
                        s.transforms[static_cast<std::size_t>(y)], clearance, scratch, &w);
        witness[e] = w;
        for (std::uint32_t f = first[static_cast<std::size_t>(y)]; f < first[static_cast<std::size_t>(y) + 1];
             ++f)
          if (with[f] == static_cast<std::int32_t>(x)) witness[f] = w;
      }
  }
}

const Witness* ContactGraph::witness_of(std::int32_t x, std::int32_t y) const {
  if (witness.empty()) return nullptr;
  for (std::uint32_t e = first[static_cast<std::size_t>(x)]; e < first[static_cast<std::size_t>(x) + 1]; ++e)
    if (with[e] == y) return &witness[e];
  return nullptr;
}

}  // namespace canopy
