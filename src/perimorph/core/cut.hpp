#pragma once
// Geometry of a pre-crack, shared by the mesh (nodes split along it) and the
// non-local model (bonds through it removed): one tie rule for every consumer.

#include "perimorph/core/types.hpp"

namespace perimorph {

/// A planar cut (a pre-crack): the mesh splits its nodes along it
/// (mesh::split_along_cut) and the non-local model removes the bonds that
/// cross it (THEORY §4). In 1D it is a
/// point (origin), in 2D a segment (origin, origin + edge1), in 3D a
/// parallelogram (origin + s edge1 + t edge2, s, t in [0, 1]) or, with
/// `triangle`, the triangle s, t ≥ 0, s + t ≤ 1 (the pieces of a pre-crack
/// read from a mesh file, mesh::split_along_faces).
struct Cut {
  int dim = 3;
  Vec3 origin = Vec3::Zero();
  Vec3 edge1 = Vec3::Zero();
  Vec3 edge2 = Vec3::Zero();
  bool triangle = false;  ///< 3D only

  /// Unit normal of the cut's line (2D, in the xy plane) or plane (3D); e_x in 1D.
  Vec3 normal() const;
  /// True if the open segment a–b crosses the closed cut (touching its
  /// boundary counts as crossing, with a relative margin of 1e-12 of the edge
  /// lengths so that round-off in the crossing point does not decide ties).
  bool crosses(const Vec3& a, const Vec3& b) const;
  /// True if p lies on the closed cut within tolerance tol (absolute length).
  bool contains(const Vec3& p, double tol) const;
};

}  // namespace perimorph
