#pragma once
/// The leaf angle distribution of a stand: leaflet area by inclination (the angle between the
/// blade's normal and the vertical, 0 for a horizontal blade), in 5-degree bins, its mean, and
/// the G-function G(theta): the mean projection of unit leaf area onto a plane perpendicular to a
/// direction at zenith theta (Ross 1981), which sets the extinction coefficient k = G / cos theta
/// of a canopy. Computed triangle by triangle from the prototypes and transforms, so a blade bent
/// by its transform counts exactly; leaf azimuths are taken as uniform (as G is used in crop models).
#include "geometry/prototype.hpp"
#include "geometry/stand.hpp"

#include <array>
#include <cstddef>
#include <vector>

namespace canopy {

inline constexpr int kLeafAngleBins = 18;  // 5-degree bins over 0-90 degrees
inline constexpr double kLeafAngleBinDeg = 5.0;
/// The zenith angles G is given at; 57.5 degrees is where G is close to 0.5 for any distribution.
inline constexpr std::array<double, 7> kGZenithsDeg{0, 15, 30, 45, 57.5, 60, 75};

/// One plant's (or a stand's) sums: leaflet area, area per bin, area x inclination, area x the
/// azimuth-averaged |cos| of the angle between the normal and each of kGZenithsDeg.
struct LeafAngleSums {
  double area = 0;
  std::array<double, kLeafAngleBins> bins{};
  double inclination_area = 0;  // degrees x m2
  std::array<double, kGZenithsDeg.size()> g_area{};
  LeafAngleSums& operator+=(const LeafAngleSums& o);
};

/// Mean over leaf azimuth of |cos(angle between a blade of inclination theta_l and a direction at
/// zenith theta)| (both radians): cos theta cos theta_l where the blade never faces away, else
/// (a (2 phi0 - pi) + 2 b sin phi0) / pi with a = cos theta cos theta_l, b = sin theta sin theta_l,
/// phi0 = acos(-a / b).
double mean_projection(double zenith, double inclination);

/// G of one inclination class is mean_projection; of a distribution, its area-weighted mean (0.5
/// at every zenith for normals uniform on the sphere, cos theta for horizontal blades).

/// Sums of every plant's leaflet organs (kind leaflet), in plant order; each plant's sum is made
/// in organ order, so the stand's total (summed in plant order) is the same on any thread count.
std::vector<LeafAngleSums> leaf_angle_sums(const Stand& stand, PrototypeLibrary& lib);

/// The distribution from summed sums: fractions per bin, mean inclination (degrees), G at
/// kGZenithsDeg (zero area gives zeros).
struct LeafAngles {
  double leaf_area = 0;  // m2, one-sided
  std::array<double, kLeafAngleBins> area{}, fraction{};
  double mean_inclination_deg = 0;
  std::array<double, kGZenithsDeg.size()> g{};
};
LeafAngles leaf_angles(const LeafAngleSums& total);
LeafAngles leaf_angles(const std::vector<LeafAngleSums>& per_plant);

}  // namespace canopy
