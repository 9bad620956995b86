#pragma once
/// Organ kinds and prototypes (docs/design.md "Organs"), with their names in grammar files and exports.
#include "geometry/hd.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

namespace canopy {

enum class OrganKind : std::uint8_t { internode, petiole, rachis, leaflet, peduncle, fruit, flower };
inline constexpr std::array<std::string_view, 7> kOrganKindNames{"internode", "petiole", "rachis", "leaflet",
                                                                 "peduncle",  "fruit",   "flower"};

enum class PrototypeKind : std::uint8_t { cylinder, leaflet, sphere, disk };
inline constexpr std::array<std::string_view, 4> kPrototypeNames{"cylinder", "leaflet", "sphere", "disk"};
/// Parameters each prototype takes from its module, in order: cylinder(length, radius),
/// leaflet(length, width), sphere(radius), disk(radius). A leaflet takes up to three more, its
/// curvature (geometry/leaflet_shape.hpp): leaflet(length, width, bend, cup, fold), those left
/// out 0.
inline constexpr std::array<int, 4> kPrototypeArity{2, 2, 1, 1};
inline constexpr std::array<int, 4> kPrototypeMaxArity{2, 5, 1, 1};

/// Solids: closed cylinders and spheres contain what lies inside them (both backends' exact test).
CANOPY_HD inline bool is_solid(PrototypeKind k) {
  return k == PrototypeKind::cylinder || k == PrototypeKind::sphere;
}

inline std::string_view name_of(OrganKind k) { return kOrganKindNames[static_cast<int>(k)]; }
inline std::string_view name_of(PrototypeKind k) { return kPrototypeNames[static_cast<int>(k)]; }
inline int arity_of(PrototypeKind k) { return kPrototypeArity[static_cast<int>(k)]; }
inline int max_arity_of(PrototypeKind k) { return kPrototypeMaxArity[static_cast<int>(k)]; }

inline std::optional<OrganKind> parse_organ_kind(std::string_view s) {
  for (std::size_t i = 0; i < kOrganKindNames.size(); ++i)
    if (kOrganKindNames[i] == s) return static_cast<OrganKind>(i);
  return std::nullopt;
}
inline std::optional<PrototypeKind> parse_prototype(std::string_view s) {
  for (std::size_t i = 0; i < kPrototypeNames.size(); ++i)
    if (kPrototypeNames[i] == s) return static_cast<PrototypeKind>(i);
  return std::nullopt;
}

}  // namespace canopy
