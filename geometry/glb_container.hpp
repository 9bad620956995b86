#pragma once
/// The GLB container (glTF 2.0 §4.4) and the per-kind material shared by both glb writers.
#include "geometry/atomic_file.hpp"
#include "geometry/organ_kind.hpp"

#include <string>

namespace canopy {

/// Pads `json` with spaces to 4 bytes, then writes the GLB header, the JSON chunk and, when
/// `bin_bytes` > 0 (a multiple of 4), the BIN chunk's header: the caller writes the BIN bytes
/// next. Throws when the file would pass the format's 4 GiB limit.
void begin_glb(AtomicFile& out, std::string& json, std::size_t bin_bytes);

/// The material of an organ kind: its colour, double-sided, not metallic.
std::string material_json(OrganKind kind);

}  // namespace canopy
