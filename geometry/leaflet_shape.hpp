#pragma once
/// The shape of a curved leaflet (docs/design.md "Organs": `leaflet(length, width, bend, cup, fold)`),
/// kept in one byte of the organ's record so that detection still reads 64 bytes per organ and
/// every organ of one shape and level of detail shares one mesh, as flat leaflets do (Helios'
/// plant architecture model likewise instances a handful of leaf prototypes per plant type,
/// `unique_prototypes = 5` for its tomato). The three angles are in degrees:
///   bend  the turn of the midrib from base to tip, a circular arc; negative: the tip droops
///   cup   the turn of the blade across it, from the midrib to each margin, a circular arc;
///         positive: the margins curl up (cupping), negative: down (rolling)
///   fold  the angle each half of the blade rises from the midrib (a crease along it)
/// Each is rounded to the nearest multiple of its step; a value outside its range is refused.
/// Code 0 is the flat leaflet, whose mesh is the flat blade's, byte for byte.
#include "geometry/hd.hpp"

#include <cmath>
#include <cstdint>
#include <optional>
#include <sstream>
#include <string>

namespace canopy {

struct LeafletShape {
  double bend_deg = 0, cup_deg = 0, fold_deg = 0;
};

/// Steps and ranges of the three angles: bend 4 bits (two's complement), cup 2 bits (two's
/// complement), fold 2 bits (0 and up): bend -80..70 by 10, cup -30..15 by 15, fold 0..30 by 10.
inline constexpr double kBendStepDeg = 10, kCupStepDeg = 15, kFoldStepDeg = 10;
inline constexpr int kBendMin = -8, kBendMax = 7, kCupMin = -2, kCupMax = 1, kFoldMin = 0, kFoldMax = 3;

/// The width-to-length ratio for which the midrib's arc is exact: the mesh lives in the organ's
/// frame, whose normal is scaled by the width, so a leaflet of another ratio r has its midrib's
/// rise scaled by r / 0.5 (Helios' tomato leaf aspect ratio; this grammar's leaflets are 0.5-0.55).
inline constexpr double kNominalLeafletAspect = 0.5;

/// The shape of code `code` (the quantised angles).
inline LeafletShape leaflet_shape(std::uint8_t code) {
  const auto sext = [](int v, int bits) { return v >= (1 << (bits - 1)) ? v - (1 << bits) : v; };
  return {kBendStepDeg * sext(code >> 4, 4), kCupStepDeg * sext((code >> 2) & 3, 2),
          kFoldStepDeg * (code & 3)};
}

/// The code of the nearest shape, or nothing when an angle lies outside its range (by more than
/// half a step) or is not finite; `what` then names the angle and its range.
inline std::optional<std::uint8_t> leaflet_shape_code(const LeafletShape& s, std::string* what = nullptr) {
  struct Angle {
    const char* name;
    double value, step;
    int lo, hi;
  };
  const Angle angles[3] = {{"bend", s.bend_deg, kBendStepDeg, kBendMin, kBendMax},
                           {"cup", s.cup_deg, kCupStepDeg, kCupMin, kCupMax},
                           {"fold", s.fold_deg, kFoldStepDeg, kFoldMin, kFoldMax}};
  int q[3];
  for (int k = 0; k < 3; ++k) {
    const Angle& a = angles[k];
    const double steps = a.value / a.step;
    if (!std::isfinite(steps) || steps < a.lo - 0.5 || steps >= a.hi + 0.5) {
      if (what) {
        std::ostringstream o;
        o << "leaflet " << a.name << " must lie in [" << a.lo * a.step << ", " << a.hi * a.step
          << "] degrees (got " << a.value << ")";
        *what = o.str();
      }
      return std::nullopt;
    }
    q[k] = static_cast<int>(std::lround(steps));
    if (q[k] < a.lo) q[k] = a.lo;  // -x.5 rounds away from zero, past the range
  }
  return static_cast<std::uint8_t>(((q[0] & 15) << 4) | ((q[1] & 3) << 2) | (q[2] & 3));
}

/// Meshes per prototype and level of detail: the four flat prototypes, then one slot per curved
/// leaflet shape (1..255).
inline constexpr int kShapeCount = 256;
inline constexpr int kMeshKinds = 4 + kShapeCount - 1;

/// The index of a prototype mesh among kMeshKinds x (max lod + 1) slots: prototype p (0-3) at
/// shape 0, curved leaflet shape s at 3 + s.
CANOPY_HD inline int mesh_kind(int prototype, int shape) { return shape ? 3 + shape : prototype; }

}  // namespace canopy
