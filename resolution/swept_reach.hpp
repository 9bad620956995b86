#pragma once
/// How far out a plant can reach under any turns resolution may make: rigid turns about joints
/// keep every distance along the structure tree, so an organ below the first turnable joint of
/// its chain (whose joint stays put, its parent never turning) stays within the summed
/// joint-to-joint lengths of that chain plus its own extent from its joint. Tiles (distributed/)
/// size their halos from it, so what a plant may touch during resolution is always on hand.
#include "collision/mbvt.hpp"
#include "geometry/prototype.hpp"
#include "geometry/stand.hpp"

namespace canopy {

/// The largest horizontal distance from plant p's origin (metres) that any point of its organs'
/// bounding boxes can reach when organs of the `movable` kinds turn by any angle.
double swept_reach(const Stand& stand, PrototypeLibrary& lib, std::size_t p, const KindMask& movable);

}  // namespace canopy
