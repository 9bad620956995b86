#pragma once
/// Where light comes from: the sun's position and a sky discretised into directions of equal
/// solid angle, with each direction's share of the diffuse irradiance on a horizontal surface.
/// Angles in degrees. The stand's frame: +Z up, +Y north, +X east (rows along +X run east-west);
/// azimuths are compass bearings, clockwise from north.
#include "geometry/vec.hpp"

#include <string>
#include <vector>

namespace canopy::light {

/// Unit vector pointing toward a source at `elevation` above the horizon and compass `azimuth`.
Vec3d toward(double elevation_deg, double azimuth_deg);

enum class SkyModel {
  uniform,  // radiance the same in every direction
  soc,      // standard overcast sky (Moon and Spencer 1942): radiance (1 + 2 cos zenith) / 3 of the zenith's
};
/// "uniform" or "soc"; throws std::invalid_argument otherwise.
SkyModel parse_sky(const std::string& name);
const char* sky_name(SkyModel m);

struct SkyDirection {
  double elevation_deg = 90, azimuth_deg = 0;
  /// The direction's share of the diffuse irradiance on a horizontal surface (weights sum to 1).
  double weight = 0;
};

/// Upper bound on --sky-directions.
inline constexpr int kMaxSkyDirections = 10000;

/// `n` directions of equal solid angle (2 pi / n sr each): the hemisphere cut into rings whose
/// cell counts grow as 1, 3, 5, ... (the zenith cell alone in the first), ring borders at equal
/// area, each direction at its cell's area midpoint in zenith and its middle in azimuth (rings
/// staggered by half a cell). Weights integrate radiance x cos(zenith) over each cell exactly.
/// Throws std::invalid_argument when n is not in 1..kMaxSkyDirections.
std::vector<SkyDirection> sky_directions(SkyModel model, int n);

struct SunPosition {
  double elevation_deg = 0, azimuth_deg = 0;
};
/// The sun at `latitude` (degrees, north positive), day of the year `day` (1-366) and local solar
/// time `hour` (0-24): declination by Cooper (1969), delta = 23.45 sin(360 (284 + day) / 365);
/// hour angle 15 (hour - 12) degrees; elevation and azimuth by the spherical-astronomy relations
/// in Iqbal, "An Introduction to Solar Radiation" (1983), ch. 1. Throws std::invalid_argument on
/// values out of range.
SunPosition solar_position(double latitude_deg, int day, double hour);

}  // namespace canopy::light
