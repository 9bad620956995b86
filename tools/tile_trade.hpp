#pragma once
/// What the ranks of a tiled run trade (collectives over every rank): per-level contact counts,
/// the turns of plants other ranks hold in their halos, the contacts left unresolved.
#include "tools/stand_tiled.hpp"

namespace canopy::cli {

/// The export scope of the plants this rank owns, numbered as in the whole stand.
ExportScope owned_scope(const Tile& t, const PlantScan& scan);

/// Detection at `level` and, with `lower_levels`, every level below it, each counted over the
/// contacts this rank owns (a contact belongs to the owner of its first plant) and summed over
/// the ranks. Returns the counts with this rank's own pairs at `level`; `all` gets every pair
/// at `level` found on the tile (the backend's tree is left at that level).
Contacts detect_owned(DetectionBackend& backend, const Tile& t, DetectRequest req, ContactLevel level,
                      bool lower_levels, Contacts* all = nullptr);

/// Sends this rank's turns to the ranks holding their plants; returns the turns made elsewhere
/// on this rank's halo plants (local organ ids both ways).
std::vector<Turn> exchange_turns(const Tile& t, const std::vector<Turn>& mine);

/// Every rank's unresolved contacts, in global ids and contact order.
std::vector<UnresolvedContact> gather_unresolved(const ExportScope& e,
                                                 const std::vector<UnresolvedContact>& mine);

}  // namespace canopy::cli
