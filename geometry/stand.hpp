#pragma once
/// The Stand: every organ of every plant in flat arrays (structure of arrays). Detection reads
/// `transforms` and `organs` only: 48 + 16 = 64 bytes per organ. Prototype parameters (for
/// exports) and joint limits (for resolution) live in arrays of their own.
#include "geometry/organ_kind.hpp"
#include "geometry/vec.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace canopy {

/// What detection needs of an organ besides its transform; ids are global in the stand.
struct OrganRecord {
  std::int32_t plant = 0;
  std::int32_t parent = -1;  // -1 at a plant's root
  std::int32_t leaf = -1;    // compound leaf, -1 outside one
  OrganKind kind = OrganKind::internode;
  PrototypeKind prototype = PrototypeKind::cylinder;
  std::uint8_t lod = 2;
  std::uint8_t shape = 0;  // a curved leaflet's shape code (geometry/leaflet_shape.hpp), 0: flat
};
static_assert(sizeof(OrganRecord) == 16);
static_assert(sizeof(Affine3f) == 48);

struct PlantRecord {
  double x = 0, y = 0;      // origin, metres (double: fields kilometres wide keep micrometres)
  double rotation_deg = 0;  // about +Z
  std::uint64_t seed = 0;
  int grammar = 0;  // index into Stand::grammars
  int steps = 0;
  std::uint32_t first_organ = 0, organ_count = 0;
  std::uint32_t first_leaf = 0, leaf_count = 0;
};

struct Stand {
  /// Prototype frame -> plant frame: the plant's rotation applied, its origin not.
  std::vector<Affine3f> transforms;
  std::vector<OrganRecord> organs;
  std::vector<std::array<float, 2>> params;  // prototype parameters, in order
  std::vector<float> joint_limit_deg;        // for resolution
  std::vector<PlantRecord> plants;
  std::vector<std::string> grammars;  // grammar files (as given) the plants came from
  Vec3d stand_origin;                 // the first plant's origin

  std::size_t organ_count() const { return organs.size(); }
  std::size_t plant_count() const { return plants.size(); }
  /// The origin of plant p relative to stand_origin, in double.
  Vec3d offset(std::size_t p) const {
    return {plants[p].x - stand_origin.x, plants[p].y - stand_origin.y, 0};
  }
};

}  // namespace canopy
