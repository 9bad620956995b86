#pragma once
/// Turtle interpretation (ABOP §1.5, §2.2): the interpreted module string becomes organ instances
/// in the plant's frame (before the plant's rotation), with their structure-tree parents and
/// compound-leaf ids. Initial frame H = +Z, L = -Y, U = +X; `+` turns left about U (R_U),
/// `&` pitches down about L (R_L), `\` rolls left about H (R_H), as ABOP's matrices.
#include "geometry/organ_kind.hpp"
#include "geometry/organ_extent.hpp"
#include "geometry/vec.hpp"
#include "lsystem/grammar.hpp"
#include "lsystem/module_string.hpp"

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace canopy {

/// The turtle's frame at an organ: where it is attached and how it is oriented when grown.
struct TurtleFrame {
  Vec3d position;
  Vec3d heading{0, 0, 1}, left{0, -1, 0}, up{1, 0, 0};
};

struct OrganInstance {
  OrganKind kind = OrganKind::internode;
  PrototypeKind prototype = PrototypeKind::cylinder;
  float params[2] = {0, 0};  // the prototype's parameters, in order
  std::uint8_t shape = 0;    // a curved leaflet's shape (its parameters 3-5, geometry/leaflet_shape.hpp)
  int parent = -1;           // index in this plant, -1 at a root
  int leaf = -1;             // compound leaf in this plant, -1 outside one
  int lod = 2;
  float joint_limit_deg = 60;
  Affine3f transform;        // prototype frame -> plant frame
  std::uint32_t module = 0;  // index in the interpreted string, for messages
};

struct TurtleResult {
  std::vector<OrganInstance> organs;
  int leaf_count = 0;
};

struct TurtleConfig {
  int lod = 2;  // default level of detail for organs without their own
  /// Names the plant in error messages ("plant 3 (seed 17)").
  std::string where = "the plant";
};

/// A problem with one module of the string the turtle runs: what() is "FILE: WHERE, module I
/// 'TEXT': WHAT"; `detail()` is the part after "FILE: ", for a message located elsewhere.
class TurtleError : public std::runtime_error {
 public:
  TurtleError(const std::string& file, std::string detail, std::size_t module, int parameter)
      : std::runtime_error(file + ": " + detail), detail_(std::move(detail)), module_(module),
        parameter_(parameter) {}
  const std::string& detail() const { return detail_; }
  /// The module's index in the string.
  std::size_t module() const { return module_; }
  /// The parameter at fault (0-based), or -1 for the module as a whole.
  int parameter() const { return parameter_; }

 private:
  std::string detail_;
  std::size_t module_;
  int parameter_;
};

/// Throws TurtleError naming the plant and module when a parameter is not finite, a length or
/// radius is negative or larger than kMaxOrganExtent, or an organ lies farther than that from the
/// plant's origin.
TurtleResult run_turtle(const Grammar& g, const ModuleString& s, const TurtleConfig& config);

/// The organ transform for `prototype` with `params` at `frame` (docs/design.md "Organs").
Affine3f organ_transform(PrototypeKind prototype, const float* params, const TurtleFrame& frame);

}  // namespace canopy
