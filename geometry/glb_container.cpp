#include "geometry/glb_container.hpp"

#include "geometry/organ_mesh.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <stdexcept>

namespace canopy {

std::string glb_header(std::uint64_t json_bytes, std::uint64_t bin_bytes) {
  constexpr std::uint32_t kGlbMagic = 0x46546C67, kJsonChunk = 0x4E4F534A;
  const std::uint64_t total = 12 + 8 + json_bytes + (bin_bytes ? 8 + bin_bytes : 0);
  if (total > 0xffffffffULL)
    throw std::runtime_error(
        "stand.glb would exceed 4 GiB, the GLB limit; export fewer plants, use --glb-instancing, or obj/ply");
  const std::uint32_t header[5] = {kGlbMagic, 2, static_cast<std::uint32_t>(total),
                                   static_cast<std::uint32_t>(json_bytes), kJsonChunk};
  return std::string(reinterpret_cast<const char*>(header), sizeof header);
}

std::string glb_bin_header(std::uint64_t bin_bytes) {
  constexpr std::uint32_t kBinChunk = 0x004E4942;
  const std::uint32_t chunk[2] = {static_cast<std::uint32_t>(bin_bytes), kBinChunk};
  return std::string(reinterpret_cast<const char*>(chunk), sizeof chunk);
}

void begin_glb(AtomicFile& out, std::string& json, std::size_t bin_bytes) {
  while (json.size() % 4) json.push_back(' ');
  out.write(glb_header(json.size(), bin_bytes));
  out.write(json);
  if (bin_bytes) out.write(glb_bin_header(bin_bytes));
}

std::string material_json(OrganKind kind) {
  const Vec3f c = kind_colour(kind);
  return fmt::format(
      "{{\"name\":\"{}\",\"doubleSided\":true,\"pbrMetallicRoughness\":{{\"baseColorFactor\":[{},{},{},1.0],"
      "\"metallicFactor\":0.0,\"roughnessFactor\":0.8}}}}",
      name_of(kind), c.x, c.y, c.z);
}

}  // namespace canopy
