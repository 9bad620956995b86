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
void write_obj(const Stand& stand, PrototypeLibrary& lib, AtomicFile& obj, AtomicFile& mtl, const std::string& mtl_name);
/// stand.ply: binary little endian, float32 vertices relative to stand_origin, normals, per face
/// `plant` and `organ`.
void write_ply(const Stand& stand, PrototypeLibrary& lib, AtomicFile& out);
/// stand.glb: glTF 2.0, Y up, root node at stand_origin, one node and mesh per plant, one
/// primitive per organ kind, `_ORGAN` vertex attribute, one material per kind, UVs on leaflets.
void write_glb(const Stand& stand, PrototypeLibrary& lib, AtomicFile& out);
/// stand.glb with one shared mesh per prototype, level of detail and kind, drawn per organ
/// through EXT_mesh_gpu_instancing (translation, rotation, scale and `_ORGAN` per instance).
void write_glb_instanced(const Stand& stand, PrototypeLibrary& lib, AtomicFile& out);

/// organs.csv: id,plant,parent,kind,leaf,area,length then prototype,p0,p1,lod,joint_limit and the
/// plant-frame transform (columns h, l, u and joint t), enough to read the stand back.
void write_organs_csv(const Stand& stand, PrototypeLibrary& lib, AtomicFile& out);
/// plants.csv: id,x,y,rotation,seed,grammar,steps.
void write_plants_csv(const Stand& stand, AtomicFile& out);
/// The same writers over an ExportScope (a tile's plants with global numbering) into
/// ChunkWriters: the bytes of the whole stand's file that fall to those plants (docs/design.md "Export files").
void write_obj(const ExportScope& scope, PrototypeLibrary& lib, ChunkWriter& obj, ChunkWriter& mtl, const std::string& mtl_name);
void write_ply(const ExportScope& scope, PrototypeLibrary& lib, ChunkWriter& out);
void write_glb(const ExportScope& scope, PrototypeLibrary& lib, ChunkWriter& out);
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
