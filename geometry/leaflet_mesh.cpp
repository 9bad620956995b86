#include "geometry/leaflet_mesh.hpp"

#include "geometry/prototype.hpp"

#include <cmath>
#include <numbers>
#include <vector>

namespace canopy {
namespace {

constexpr double kRad = std::numbers::pi / 180;

/// The blade surface: a point (s along the midrib, y across it, the flat blade's coordinates)
/// and the surface's normal there, in the prototype's frame (x along the heading in lengths, y
/// and z in widths).
struct Surface {
  double bend, cup_rate, fold;  // radians; cup_rate: the cross-section's turn per unit of width
  double a0 = kNominalLeafletAspect;

  /// The cross-section at distance u >= 0 from the midrib: across (Y) and up (Z), and its angle.
  void section(double u, double& Y, double& Z, double& alpha) const {
    alpha = fold + cup_rate * u;
    if (std::fabs(cup_rate) > 1e-12) {
      Y = (std::sin(alpha) - std::sin(fold)) / cup_rate;
      Z = (std::cos(fold) - std::cos(alpha)) / cup_rate;
    } else {
      Y = u * std::cos(fold);
      Z = u * std::sin(fold);
    }
  }

  Vec3d point(double s, double y) const {
    double Y, Z, alpha;
    section(std::fabs(y), Y, Z, alpha);
    const double phi = bend * s;
    // The midrib's arc (in lengths), then the cross-section on its normal (-sin, cos) in x-z.
    const double X = std::fabs(bend) > 1e-12 ? std::sin(phi) / bend : s;
    const double Zm = std::fabs(bend) > 1e-12 ? (1 - std::cos(phi)) / bend : 0;
    return {X - a0 * Z * std::sin(phi), y < 0 ? -Y : Y, Zm / a0 + Z * std::cos(phi)};
  }

  /// d/ds x d/dy of point(), on the side of the midrib that `side` (+1 or -1) says.
  Vec3d normal(double s, double y, double side) const {
    double Y, Z, alpha;
    section(std::fabs(y), Y, Z, alpha);
    const double phi = bend * s, c = std::cos(phi), sn = std::sin(phi);
    const Vec3d ts{c * (1 - a0 * Z * bend), 0, sn * (1 / a0 - Z * bend)};
    const Vec3d ty{-side * a0 * std::sin(alpha) * sn, std::cos(alpha), side * std::sin(alpha) * c};
    return normalized(cross(ts, ty));
  }

  Vec3f vertex_normal(double s, double y) const {
    if (y != 0) return to_float(normal(s, y, y < 0 ? -1 : 1));
    return to_float(normalized(normal(s, 0, 1) + normal(s, 0, -1)));
  }
};

}  // namespace

PrototypeMesh curved_leaflet(int lod, const LeafletShape& shape) {
  PrototypeMesh m;
  const Surface f{shape.bend_deg * kRad, shape.cup_deg * kRad / 0.5, shape.fold_deg * kRad};
  // Columns a side: the margins alone where the blade is straight across (then the flat blade's
  // triangles), the midrib too where it is folded, lod columns where it is cupped.
  const int cols = shape.cup_deg != 0 ? lod : shape.fold_deg != 0 ? 1 : 0;
  const auto add = [&](double s, double y) {
    m.positions.push_back(to_float(f.point(s, y)));
    m.normals.push_back(f.vertex_normal(s, y));
    m.uvs.push_back({static_cast<float>(s), static_cast<float>(0.5 + y)});
    return static_cast<std::uint32_t>(m.positions.size() - 1);
  };
  const auto tri = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    m.indices.insert(m.indices.end(), {a, b, c});
  };
  // Stations as the flat blade's (s = t^2), each a row of vertices from the right margin (y < 0)
  // to the left one; the half-widths are the flat blade's, rounded to float as it rounds them.
  const int n = 4 * lod + 1;
  const std::uint32_t base = add(0, 0);
  std::vector<std::vector<std::uint32_t>> rows;
  for (int i = 1; i < n; ++i) {
    const double t = static_cast<double>(i) / n;
    const double s = static_cast<double>(static_cast<float>(t * t));
    const double w = static_cast<double>(static_cast<float>(leaflet_half_width(t * t)));
    std::vector<std::uint32_t> row;
    if (cols == 0) {
      row = {add(s, -w), add(s, w)};
    } else {
      for (int j = -cols; j <= cols; ++j) row.push_back(add(s, w * j / cols));
    }
    rows.push_back(std::move(row));
  }
  const std::uint32_t tip = add(1, 0);
  // Counter-clockwise seen from the blade's upper side (+z of the flat blade).
  for (std::size_t j = 0; j + 1 < rows.front().size(); ++j) tri(base, rows.front()[j], rows.front()[j + 1]);
  for (std::size_t i = 0; i + 1 < rows.size(); ++i)
    for (std::size_t j = 0; j + 1 < rows[i].size(); ++j) {
      tri(rows[i][j], rows[i + 1][j], rows[i + 1][j + 1]);
      tri(rows[i][j], rows[i + 1][j + 1], rows[i][j + 1]);
    }
  for (std::size_t j = 0; j + 1 < rows.back().size(); ++j) tri(rows.back()[j], tip, rows.back()[j + 1]);
  return m;
}

}  // namespace canopy
