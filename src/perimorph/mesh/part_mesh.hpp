#pragma once
// A process's piece of the mesh (issue 17, item 1): the cells it owns and its
// halo, as a mesh of their own numbered locally, with the global number of
// every local cell and node. Local numbers keep the global order (cells and
// nodes sorted by global number), so that a dof map built on the piece lists
// its nodes in the order the whole model's does (partition::part_dof_numbering
// relies on it), and a pass over the local cells visits them in serial order.

#include "perimorph/core/types.hpp"
#include "perimorph/mesh/mesh.hpp"

#include <span>
#include <vector>

namespace perimorph::mesh {

struct PartMesh {
  Mesh mesh;
  /// The global number of each local cell, ascending.
  std::vector<Index> global_cell;
  /// The global number of each local node, ascending.
  std::vector<Index> global_node;

  /// The local number of global cell c, or -1 if the piece lacks it (a search).
  Index local_cell(Index c) const;
  /// The local number of global node n, or -1 if the piece lacks it (a search).
  Index local_node(Index n) const;
};

/// The piece of `whole` made of `cells` (global numbers, each once, any
/// order) and the nodes they use. Node sets keep their nodes in the piece,
/// face and cell sets their faces and cells in it; every set keeps its name,
/// empty where the piece has none of it, so that a boundary condition on a set
/// names a set on every process. Region ids and cuts are kept, and a
/// structured layout, with the box cell of each local cell
/// (StructuredLayout::box_cells). Throws Error for a cell out of range or
/// listed twice.
PartMesh part_mesh(const Mesh& whole, std::span<const Index> cells);

}  // namespace perimorph::mesh
