#pragma once
// Geometry of a hole, shared by the case file (which names it) and the mesh
// (which removes the cells inside it, mesh::remove_hole).

#include "perimorph/core/types.hpp"

#include <string>

namespace perimorph {

/// disk: 2D, a circle in the xy plane; ball: 3D, a sphere; cylinder: 3D, a
/// circular cylinder of infinite length with its axis along z; box: any
/// dimension, an axis-aligned box.
enum class HoleShape { disk, ball, cylinder, box };

/// A hole in a mesh of dimension `dim`: a disk, ball or cylinder (center,
/// radius; the cylinder's axis is the line through center parallel to z) or a
/// box (lower, upper; the first dim components are used).
struct Hole {
  int dim = 2;
  HoleShape shape = HoleShape::disk;
  Vec3 center = Vec3::Zero();
  double radius = 0.0;
  Vec3 lower = Vec3::Zero();
  Vec3 upper = Vec3::Zero();

  /// True if x lies strictly inside the shape (a point on its boundary is outside).
  bool contains(const Vec3& x) const;
  /// For messages: "disk of radius 0.3 centred at [2, 1]", "box [0, 0] to [1, 2]".
  std::string describe() const;
};

}  // namespace perimorph
