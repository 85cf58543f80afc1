#pragma once
// Structured box meshes (bars, quads, hexes) with named boundary sets.

#include "perimorph/mesh/mesh.hpp"

#include <array>

namespace perimorph::mesh {

struct BoxSpec {
  int dim = 3;
  Vec3 lower = Vec3::Zero();
  Vec3 upper = Vec3::Ones();
  std::array<Index, 3> cells{1, 1, 1};  ///< cells per direction (first dim used)
};

/// A structured mesh of the box. Nodes are numbered x fastest, cells likewise.
/// Named sets: node and face sets "xmin", "xmax", "ymin", ... (only for the
/// box's own dimension), node set "boundary" (every boundary node), face set
/// "boundary", cell set "all".
Mesh make_box(const BoxSpec& spec);

}  // namespace perimorph::mesh
