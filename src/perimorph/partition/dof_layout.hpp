#pragma once
// The dofs of a partitioned discretization (issue 17, item 2): who owns each
// dof node, a numbering in which every part's owned nodes are contiguous (the
// row ranges of PETSc's distributed matrices and vectors), and the ghost nodes
// each part writes into or reads: those of the cells it assembles that another
// part owns.
//
// Who assembles what, so that each cell and each bond is assembled once: part
// p assembles the local block of the cells it owns, and the bonds of every
// cell pair (E, F), E ≤ F, of the cell graph with E owned by p (THEORY §4: a
// pair's bonds are one block over both cells' nodes).
//
// Node ownership: the node of a discontinuous cell (DG, private to it) belongs
// to the cell's owner; a continuous (CG) node shared by cells of several parts
// belongs to the lowest of those parts; a node of no cell, to part 0. The numbering keeps the serial order
// within a part, so one part gives the serial numbering back.
//
// Serial for now: every rank holds the whole mesh and the same layout; what a
// rank needs of it is its range and its ghosts.

#include "perimorph/core/types.hpp"
#include "perimorph/partition/partition.hpp"

#include <algorithm>
#include <vector>

namespace perimorph::dofs {
class DofMap;
}
namespace perimorph::partition {

/// The part that assembles the bonds of the cell pair {e, f}: the owner of the
/// lower-numbered cell.
inline int pair_assembler(const Partition& p, Index e, Index f) {
  return p.owner[static_cast<std::size_t>(std::min(e, f))];
}

struct DofLayout {
  int parts = 1;
  /// The owning part of each dof node (serial numbering).
  std::vector<int> node_owner;
  /// The distributed number of each dof node (serial numbering in, a
  /// permutation of 0 … nodes − 1 out).
  std::vector<Index> to_distributed;
  /// Part p owns the distributed nodes [part_offsets[p], part_offsets[p + 1]).
  std::vector<Index> part_offsets;
  /// Per part, the nodes (serial numbering, sorted) of the cells it assembles
  /// (its own cells and the second cells of its pairs) owned by another part.
  std::vector<std::vector<Index>> ghosts;

  Index num_nodes() const { return static_cast<Index>(node_owner.size()); }
  Index owned_nodes(int part) const {
    return part_offsets[static_cast<std::size_t>(part) + 1] - part_offsets[static_cast<std::size_t>(part)];
  }
  /// Σ ghosts / Σ owned nodes: the halo's share of the nodes a rank holds.
  double ghost_ratio() const;
};

/// The layout of `dofmap`'s nodes over the parts of `p` (one owner per cell of
/// dofmap's mesh), with the cell pairs of `graph` (the local model's diagonal
/// graph for no bonds). Throws Error if the sizes disagree.
DofLayout dof_layout(const dofs::DofMap& dofmap, const Partition& p, const bonds::CellGraph& graph);

}  // namespace perimorph::partition
