#pragma once
/// The GLB container (glTF 2.0 §4.4) and the per-kind material shared by both glb writers.
#include "geometry/atomic_file.hpp"
#include "geometry/organ_kind.hpp"

#include <cstdint>
#include <string>

namespace canopy {

/// The GLB header and the JSON chunk's header (20 bytes) for a JSON chunk of `json_bytes` (a
/// multiple of 4) and a BIN chunk of `bin_bytes`; throws past the format's 4 GiB limit.
std::string glb_header(std::uint64_t json_bytes, std::uint64_t bin_bytes);
/// The BIN chunk's header (8 bytes).
std::string glb_bin_header(std::uint64_t bin_bytes);

/// Pads `json` with spaces to 4 bytes, then writes the GLB header, the JSON chunk and, when
/// `bin_bytes` > 0 (a multiple of 4), the BIN chunk's header: the caller writes the BIN bytes
/// next. Throws when the file would pass the format's 4 GiB limit.
void begin_glb(AtomicFile& out, std::string& json, std::size_t bin_bytes);

/// The material of an organ kind: its colour, double-sided, not metallic.
std::string material_json(OrganKind kind);

}  // namespace canopy
