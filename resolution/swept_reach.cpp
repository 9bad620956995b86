#include "resolution/swept_reach.hpp"

#include "geometry/obb.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace canopy {
namespace {

double norm3(double x, double y, double z) { return std::sqrt(x * x + y * y + z * z); }

}  // namespace

double swept_reach(const Stand& s, PrototypeLibrary& lib, std::size_t p, const KindMask& movable) {
  const PlantRecord& pr = s.plants[p];
  const std::size_t n = pr.organ_count;
  // Per organ (plant-local index): whether it can move, the fixed joint its chain turns about,
  // and a bound on the distance from that joint to its own joint.
  std::vector<std::uint8_t> moves(n, 0);
  std::vector<Vec3d> anchor(n);
  std::vector<double> chain(n, 0);
  double reach = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t k = pr.first_organ + i;
    const OrganRecord& r = s.organs[k];
    const Affine3f& m = s.transforms[k];
    const Vec3d joint{m.t.x, m.t.y, m.t.z};
    const std::ptrdiff_t parent =
        r.parent < 0 ? -1
                     : static_cast<std::ptrdiff_t>(r.parent) - static_cast<std::ptrdiff_t>(pr.first_organ);
    const bool parent_moves = parent >= 0 && moves[static_cast<std::size_t>(parent)];
    const Obb b = make_obb(m, lib.get(r).box, 0);
    const double half_diagonal = b.radius;  // the box's bounding sphere about its centre
    if (parent_moves) {
      const Affine3f& pm = s.transforms[pr.first_organ + static_cast<std::size_t>(parent)];
      moves[i] = 1;
      anchor[i] = anchor[static_cast<std::size_t>(parent)];
      chain[i] = chain[static_cast<std::size_t>(parent)] +
                 norm3(joint.x - pm.t.x, joint.y - pm.t.y, joint.z - pm.t.z);
    } else if (movable[static_cast<std::size_t>(r.kind)]) {
      moves[i] = 1;
      anchor[i] = joint;
    }
    double out;
    if (moves[i]) {
      const double extent =
          norm3(b.centre.x - joint.x, b.centre.y - joint.y, b.centre.z - joint.z) + half_diagonal;
      out = std::hypot(anchor[i].x, anchor[i].y) + chain[i] + extent;
    } else {
      out = std::hypot(static_cast<double>(b.centre.x), static_cast<double>(b.centre.y)) + half_diagonal;
    }
    reach = std::max(reach, out);
  }
  return reach;
}

}  // namespace canopy
