#pragma once
/// Mesh and table exports of a stand (docs/design.md "Export files"). Meshes are streamed organ by organ
/// from prototypes and transforms, so a large stand never holds all its triangles in memory.
#include "geometry/atomic_file.hpp"
#include "geometry/chunked_output.hpp"
#include "geometry/prototype.hpp"
#include "geometry/stand.hpp"

#include <string>

namespace canopy {

/// stand.obj (+ stand.mtl): world metres, Z up, `o plant_<p>`, `g organ_<id>`, `usemtl <kind>`.
void write_obj(const Stand& stand, PrototypeLibrary& lib, AtomicFile& obj, AtomicFile& mtl,
               const std::string& mtl_name);
/// stand.ply: binary little endian, float32 vertices relative to stand_origin, normals, per face
/// `plant` and `organ`.
void write_ply(const Stand& stand, PrototypeLibrary& lib, AtomicFile& out);
/// stand.glb: glTF 2.0, Y up, root node at stand_origin, one node and mesh per plant, one
/// primitive per organ kind, `_ORGAN` vertex attribute, one material per kind, UVs on leaflets.
void write_glb(const Stand& stand, PrototypeLibrary& lib, AtomicFile& out);
/// The compact stand.glb (KHR_mesh_quantization): see write_glb_compact.
struct GlbCompactConfig {
  /// The coarsest position step allowed (metres). Rounding moves a vertex by at most half a step
  /// along each axis, so a step below half the resolution clearance keeps a resolved stand
  /// penetration-free; a plant too large for 65,535 such steps keeps FLOAT positions.
  double max_step = 5e-5;
};
/// A plant's organs are numbered from its first in 16 bits in the compact glb.
inline constexpr std::uint32_t kCompactOrgansPerPlant = 65536;
/// stand.glb with KHR_mesh_quantization: as write_glb (nodes, meshes, primitives, materials), but
/// each plant node translated to its box's corner and scaled by its position step; positions
/// UNSIGNED_SHORT steps, normals normalized BYTE, leaflet UVs normalized UNSIGNED_SHORT, indices
/// UNSIGNED_SHORT below 65,536 vertices a primitive; organ id = node extras.first_organ +
/// `_ORGAN` (UNSIGNED_SHORT). About half the size of write_glb's file.
void write_glb_compact(const Stand& stand, PrototypeLibrary& lib, AtomicFile& out,
                       const GlbCompactConfig& config = {});
/// stand.glb with one shared mesh per prototype, level of detail and kind, drawn per organ
/// through EXT_mesh_gpu_instancing (translation, rotation, scale and `_ORGAN` per instance).
void write_glb_instanced(const Stand& stand, PrototypeLibrary& lib, AtomicFile& out);

/// organs.csv: id,plant,parent,kind,leaf,area,length then prototype,p0,p1,lod,joint_limit and the
/// plant-frame transform (columns h, l, u and joint t), enough to read the stand back.
void write_organs_csv(const Stand& stand, PrototypeLibrary& lib, AtomicFile& out);
/// plants.csv: id,x,y,rotation,seed,grammar,steps.
void write_plants_csv(const Stand& stand, AtomicFile& out);
/// The same writers over an ExportScope (a tile's plants with global numbering) into
/// ChunkWriters: the bytes of the whole stand's file that fall to those plants (docs/design.md "Export
/// files").
void write_obj(const ExportScope& scope, PrototypeLibrary& lib, ChunkWriter& obj, ChunkWriter& mtl,
               const std::string& mtl_name);
void write_ply(const ExportScope& scope, PrototypeLibrary& lib, ChunkWriter& out);
void write_glb(const ExportScope& scope, PrototypeLibrary& lib, ChunkWriter& out);
void write_glb_compact(const ExportScope& scope, PrototypeLibrary& lib, ChunkWriter& out,
                       const GlbCompactConfig& config = {});
/// Throws std::invalid_argument naming a plant of the scope with more organs than the compact glb
/// numbers (kCompactOrgansPerPlant), so a run can refuse before its work rather than at export.
void check_glb_compact(const ExportScope& scope);
/// Throws, as the export would, when stand.glb (the default form) cannot fit the GLB format's
/// 4 GiB: checked on a lower bound of its binary chunk (every organ's vertices with position,
/// normal and id, its indices at 16 bits), so a run can refuse before its work.
void check_glb_fits(const Stand& stand, PrototypeLibrary& lib);
void write_organs_csv(const ExportScope& scope, PrototypeLibrary& lib, ChunkWriter& out);
void write_plants_csv(const ExportScope& scope, ChunkWriter& out);

/// Reads a stand back from DIR/organs.csv and DIR/plants.csv (bit-exact transforms). Only what
/// canopy writes is read: std::runtime_error names file, line and column for a missing header,
/// a cell that is not a finite number or is out of range (sizes and transform entries within
/// kMaxOrganExtent), a parent that is not an earlier organ of the same plant, or compound-leaf
/// ids out of the order the turtle numbers them; InputFile's limits apply to both files.
Stand read_stand(const std::string& dir);

/// glTF's Y-up frame from canopy's Z-up one: (x, y, z) -> (x, z, -y).
inline Vec3f to_y_up(Vec3f v) { return {v.x, v.z, -v.y}; }

}  // namespace canopy
