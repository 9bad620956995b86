#pragma once
// A plain reference for the triangle tests: the distance of two closed triangles as 0 where they
// meet, otherwise the least of the six vertex-triangle and nine edge-edge distances, with none of
// the quick rejections (plane, edge-axis, float pre-tests) that the predicates under test try first.
#include "geometry/triangle_distance.hpp"

#include <algorithm>
#include <cmath>

namespace canopy::test {

inline double reference_distance(const Vec3f* p, const Vec3f* q) {
  if (triangles_intersect(p, q)) return 0;
  D3 a[3], b[3];
  for (int i = 0; i < 3; ++i) a[i] = d3(p[i]), b[i] = d3(q[i]);
  double d2 = 1e300;
  for (int i = 0; i < 3; ++i) {
    d2 = std::min({d2, point_triangle_dist2(a[i], b), point_triangle_dist2(b[i], a)});
    for (int j = 0; j < 3; ++j)
      d2 = std::min(d2, segment_segment_dist2(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3]));
  }
  return std::sqrt(d2);
}

}  // namespace canopy::test
