#pragma once
/// Axis-aligned boxes kept in lanes of 8 floats (structure of arrays), so that the CPU backend
/// tests 8 box pairs at once (collision/organ_rows.hpp): every cluster's organs' boxes
/// (obb_aabb), and every plant's clusters' boxes (Cluster::box). Part of the MBVT on the host:
/// fit with the OBBs (fit_mbvt) and refit with them (refit_mbvt), a box per organ and cluster.
#include "geometry/lcd.hpp"
#include "geometry/prototype.hpp"

#include <cstdint>
#include <vector>

namespace canopy {

struct Mbvt;

/// Boxes by lane; lanes no box was set in hold an empty box (meeting nothing).
struct BoxLanes {
  std::vector<float> lo_x, lo_y, lo_z, hi_x, hi_y, hi_z;
  void assign_empty(std::size_t lanes);
  void set(std::size_t lane, const Box3f& b) {
    lo_x[lane] = b.lo.x, lo_y[lane] = b.lo.y, lo_z[lane] = b.lo.z;
    hi_x[lane] = b.hi.x, hi_y[lane] = b.hi.y, hi_z[lane] = b.hi.z;
  }
  Box3f get(std::size_t lane) const {
    return Box3f{{lo_x[lane], lo_y[lane], lo_z[lane]}, {hi_x[lane], hi_y[lane], hi_z[lane]}};
  }
};

struct OrganLanes {
  static constexpr std::uint32_t kWidth = 8;
  /// Cluster c's k-th organ (cluster_organs[c.first + k]) at lane organ_first[c] + k; each
  /// cluster's run padded to a multiple of kWidth, with kWidth lanes more after the last.
  std::vector<std::uint32_t> organ_first;
  BoxLanes organs;
  /// Per cluster: the box around its organs' boxes (their least lo and greatest hi, so an organ
  /// box that misses it misses every one of them, exactly).
  std::vector<Box3f> around;
  /// Per cluster: its root's LCD box, lcd_centred(nodes[root].box), side by side with the other
  /// clusters' (the pass tests cluster pairs' roots without going through the cluster's index).
  std::vector<LcdCentred> roots;
  /// Plant p's k-th cluster's box at lane cluster_first[p] + k, padded the same way.
  std::vector<std::uint32_t> cluster_first;
  BoxLanes clusters;
};

/// Lays the lanes out for the tree's clusters and plants, every box empty.
void lay_out_lanes(OrganLanes& lanes, const Mbvt& m);
/// Cluster c's organ lanes and its box around them, from its organs' OBBs.
void fill_organ_lanes(OrganLanes& lanes, const Mbvt& m, std::uint32_t c);
/// Plant p's cluster lanes from its clusters' boxes (fit_plant_bound sets those).
void fill_cluster_lanes(OrganLanes& lanes, const Mbvt& m, std::uint32_t p);

}  // namespace canopy
