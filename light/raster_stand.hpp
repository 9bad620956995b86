#pragma once
/// The stand as the rasterizer draws it (light/raster.hpp): the meshes of the slots the organs
/// use, laid end to end, beside per-organ slots; the transforms are the Stand's own and each
/// organ's plant and kind the OrganIndex's (light/sampler.hpp).
/// Also the host's drawing of a direction's cells and their tally, which a device's drawing
/// (light/raster_device.hpp) shares.
#include "geometry/prototype.hpp"
#include "geometry/stand.hpp"
#include "light/raster.hpp"
#include "light/sampler.hpp"
#include "light/tally.hpp"

#include <cstdint>
#include <vector>

namespace canopy::light {

/// Whether light leaves an organ out: a solid that its transform flattens to nothing (a flat
/// blade whose third column vanishes is still a blade). The ray caster and the rasterizer agree.
bool left_out(const OrganRecord& r, const Affine3f& t);

/// The union of the boxes of the organs light keeps (metres, relative to stand_origin) and how
/// many it leaves out; false when it keeps none. The ray caster and the rasterizer share it.
bool stand_box(const Stand& s, PrototypeLibrary& lib, Vec3d& lo, Vec3d& hi, std::size_t& left);

class RasterStand {
 public:
  /// Keeps references to `s` (its transforms are drawn in place) and `organs`.
  RasterStand(const Stand& s, PrototypeLibrary& lib, const OrganIndex& organs);
  RasterStand(const RasterStand&) = delete;
  RasterStand& operator=(const RasterStand&) = delete;
  const RasterView& view() const { return view_; }
  /// Triangles drawn per direction: every organ's mesh.
  std::uint64_t triangles() const { return triangles_; }

 private:
  std::vector<Vec3f> positions_;
  std::vector<std::uint32_t> indices_, tri_first_, tri_count_, vertex_first_;
  std::vector<std::int16_t> slot_;
  std::vector<Vec3d> offset_;
  RasterView view_;
  std::uint64_t triangles_ = 0;
};

/// The grid of `job` as the rasterizer reads it (the ray caster draws its points from it too).
RasterGrid raster_grid(const DirectionJob& job);

/// Draws the stand over `g` on the host's threads: cells (nx * ny, zeroed) get their keys.
void rasterize(const RasterView& v, const RasterGrid& g, std::uint64_t* cells);

/// What a cell's key means for the tally: its plant, kind, leaflet flag and height layer.
Outcome outcome_of(std::int64_t organ, double z, const OrganIndex& organs, double layer_m,
                   std::size_t layers);

/// The tally of a direction's cells (pairs of neighbours as trace_direction takes them).
Tally tally_cells(const std::uint64_t* cells, const DirectionJob& job, const OrganIndex& organs,
                  std::size_t plants);

}  // namespace canopy::light
