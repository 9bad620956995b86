#pragma once
/// The round's contacts organ by organ, with the triangles that touch in each pair: where every
/// candidate turn of a resolution round starts its search (resolution/turn_search.hpp).
#include "collision/contacts.hpp"
#include "collision/exact.hpp"
#include "geometry/stand.hpp"

#include <cstdint>
#include <vector>

namespace canopy {

/// Which organs touch at the start of the round (the round's contact list), organ by organ.
struct ContactGraph {
  std::vector<std::uint32_t> first;  // per organ + 1
  std::vector<std::int32_t> with;
  /// Per entry of `with`: the triangles of the pair that touch now (by organ order, as
  /// organs_touch_at keeps them). Every candidate mover of a contact starts its search of that
  /// pair from them instead of finding them again with a full test.
  std::vector<Witness> witness;
  void build(std::size_t organs, const std::vector<Contact>& contacts);
  /// Fills `witness` (the exact test of each pair within `clearance`, on all threads).
  void find_witnesses(const Stand& stand, PrototypeLibrary& lib, float clearance, int threads);
  /// The witness of organs x and y, or none when they are not in the list.
  const Witness* witness_of(std::int32_t x, std::int32_t y) const;
};

}  // namespace canopy
