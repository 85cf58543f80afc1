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

/// The layout of make_box(spec) (its box_cells empty): cells per axis (1
/// beyond spec.dim), corners and spacing.
StructuredLayout box_layout(const BoxSpec& spec);

/// Node (i, j, k) of the box of `layout` in `dim` dimensions, as make_box
/// places it (the same expression: the same bits).
Vec3 box_node(const StructuredLayout& layout, int dim, const std::array<Index, 3>& ijk);

/// Box cell b of `layout` alone, as a mesh of one cell whose corners are
/// make_box's, bit for bit, in make_box's order: what a process needs of a
/// cell outside its piece of a box (the non-local assembly's translation
/// cache).
Mesh box_cell_mesh(const StructuredLayout& layout, int dim, Index b);

}  // namespace perimorph::mesh
