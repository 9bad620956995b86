#pragma once
/// The triangles of every organ of an exported stand, read back from its mesh file in world
/// coordinates (metres, Z up, double) for checks that use none of canopy's own predicates
/// (check_cgal): from stand.obj (`g organ_<id>` groups) or from stand.glb (the default or the
/// compact form: node translations and scales applied, quantized attributes decoded, ids from
/// `_ORGAN` plus the plant node's extras.first_organ where there is one).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <array>
#include <string>
#include <vector>

namespace canopy::check {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;

struct OrganGeometry {
  std::vector<Point> v;
  std::vector<std::array<int, 3>> f;  // indices into v
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  void add(double x, double y, double z);
};

/// Fills `organs` (one entry per organ id, sized by the caller) from DIR/stand.obj.
void read_obj_organs(const std::string& path, std::vector<OrganGeometry>& organs);
/// The same from a stand.glb; throws std::runtime_error on a form it does not read (instanced).
void read_glb_organs(const std::string& path, std::vector<OrganGeometry>& organs);

}  // namespace canopy::check
