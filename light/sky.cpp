#include "light/sky.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace canopy::light {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

/// Integral of radiance x cos(zenith) d(cos zenith) from c0 to c1 (c = cos zenith), up to a
/// constant factor the model's weights share.
double radiance_cos_integral(SkyModel m, double c0, double c1) {
  const auto f = [m](double c) { return m == SkyModel::uniform ? c * c / 2 : c * c / 2 + 2 * c * c * c / 3; };
  return f(c1) - f(c0);
}

}  // namespace

Vec3d toward(double elevation_deg, double azimuth_deg) {
  const double e = elevation_deg * kDeg, a = azimuth_deg * kDeg;
  return {std::cos(e) * std::sin(a), std::cos(e) * std::cos(a), std::sin(e)};
}

SkyModel parse_sky(const std::string& name) {
  if (name == "uniform") return SkyModel::uniform;
  if (name == "soc") return SkyModel::soc;
  throw std::invalid_argument(fmt::format("--sky: '{}' is not uniform or soc", name));
}

const char* sky_name(SkyModel m) { return m == SkyModel::uniform ? "uniform" : "soc"; }

std::vector<SkyDirection> sky_directions(SkyModel model, int n) {
  if (n < 1 || n > kMaxSkyDirections)
    throw std::invalid_argument(fmt::format("--sky-directions: {} is not in 1..{}", n, kMaxSkyDirections));
  // Rings: with B rings of 1, 3, 5, ... cells (B^2 in all) scaled to n, the cumulative count
  // after ring k is round(n k^2 / B^2), so cells stay about as wide as the rings are tall.
  const int rings = std::max(1, static_cast<int>(std::lround(std::sqrt(static_cast<double>(n)))));
  std::vector<int> cum(static_cast<std::size_t>(rings) + 1, 0);
  for (int k = 1; k <= rings; ++k)
    cum[static_cast<std::size_t>(k)] =
        static_cast<int>(std::lround(static_cast<double>(n) * k * k / (static_cast<double>(rings) * rings)));
  cum[1] = std::max(cum[1], 1);
  const double total = radiance_cos_integral(model, 0, 1);
  std::vector<SkyDirection> out;
  out.reserve(static_cast<std::size_t>(n));
  for (int k = 1; k <= rings; ++k) {
    const int first = cum[static_cast<std::size_t>(k) - 1], count = cum[static_cast<std::size_t>(k)] - first;
    if (count <= 0) continue;
    // A cap of zenith t holds 2 pi (1 - cos t) sr: ring borders at equal area.
    const double c_top = 1 - static_cast<double>(first) / n,
                 c_bottom = 1 - static_cast<double>(first + count) / n;
    const double c_mid = 1 - (first + 0.5 * count) / n;
    const double zenith = first == 0 && count == 1 ? 0.0 : std::acos(c_mid);
    const double w = radiance_cos_integral(model, std::max(0.0, c_bottom), c_top) / total / count;
    for (int j = 0; j < count; ++j) {
      SkyDirection d;
      d.elevation_deg = 90 - zenith / kDeg;
      d.azimuth_deg = std::fmod(360.0 * (j + 0.5 * (1 + (k % 2))) / count, 360.0);
      d.weight = w;
      out.push_back(d);
    }
  }
  return out;
}

SunPosition solar_position(double latitude_deg, int day, double hour) {
  if (!(std::abs(latitude_deg) <= 90))
    throw std::invalid_argument(fmt::format("--latitude: {} is not in -90..90", latitude_deg));
  if (day < 1 || day > 366)
    throw std::invalid_argument(fmt::format("--day: {} is not a day of the year (1..366)", day));
  if (!(hour >= 0 && hour <= 24))
    throw std::invalid_argument(fmt::format("--hours: {} is not a solar time in 0..24", hour));
  const double decl = 23.45 * kDeg * std::sin(2 * std::numbers::pi * (284 + day) / 365.0);
  const double omega = 15 * kDeg * (hour - 12), phi = latitude_deg * kDeg;
  // The unit vector toward the sun in (east, north, up).
  const double east = -std::cos(decl) * std::sin(omega);
  const double north = std::sin(decl) * std::cos(phi) - std::cos(decl) * std::sin(phi) * std::cos(omega);
  const double up = std::sin(phi) * std::sin(decl) + std::cos(phi) * std::cos(decl) * std::cos(omega);
  SunPosition s;
  s.elevation_deg = std::asin(std::clamp(up, -1.0, 1.0)) / kDeg;
  s.azimuth_deg = std::atan2(east, north) / kDeg;
  if (s.azimuth_deg < 0) s.azimuth_deg += 360;
  return s;
}

}  // namespace canopy::light
