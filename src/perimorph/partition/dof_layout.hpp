#pragma once
// The dofs of a partitioned discretization (issue 17, item 2): who owns each
// dof node, a numbering in which every part's owned nodes are contiguous (the
// row ranges of PETSc's distributed matrices and vectors), and the ghost nodes
// each part reads.
//
// Who assembles what (owner computes): a part assembles the rows of the nodes
// it owns, and nothing else. So it computes the local block of every cell with
// a node it owns (cells_touching) and the bonds of every cell pair (E, F) of
// the cell graph with E or F among them (THEORY §4: a pair's bonds are one
// block over both cells' nodes), and keeps the owned rows. Every row is then
// summed on one part, from the same cells and pairs in the same order as on
// one process: the distributed matrix is the serial one bit for bit, and no
// entry travels. A pair or cell touching two parts is computed on both.
//
// Node ownership: the node of a discontinuous cell (DG, private to it) belongs
// to the cell's owner; a continuous (CG) node shared by cells of several parts
// belongs to the lowest of those parts; a node of no cell, to part 0. The
// numbering keeps the serial order within a part, so one part gives the serial
// numbering back.
//
// Serial for now: every rank holds the whole mesh and the same layout; what a
// rank needs of it is its range and its ghosts.

#include "perimorph/core/types.hpp"
#include "perimorph/partition/partition.hpp"

#include <vector>

namespace perimorph::dofs {
class DofMap;
}

namespace perimorph::partition {

struct DofLayout {
  int parts = 1;
  /// The owning part of each dof node (serial numbering).
  std::vector<int> node_owner;
  /// The distributed number of each dof node (serial numbering in, a
  /// permutation of 0 … nodes − 1 out).
  std::vector<Index> to_distributed;
  /// Part p owns the distributed nodes [part_offsets[p], part_offsets[p + 1]).
  std::vector<Index> part_offsets;
  /// Per part, the nodes (serial numbering, sorted) another part owns that the
  /// part's rows couple to: those of the cells it computes and of their
  /// neighbours in the cell graph (empty from dof_numbering).
  std::vector<std::vector<Index>> ghosts;

  Index num_nodes() const { return static_cast<Index>(node_owner.size()); }
  Index owned_nodes(int part) const {
    return part_offsets[static_cast<std::size_t>(part) + 1] - part_offsets[static_cast<std::size_t>(part)];
  }
  /// Σ ghosts / Σ owned nodes: the halo's share of the nodes a rank holds.
  double ghost_ratio() const;
};

/// The owners and the distributed numbering of `dofmap`'s nodes over the
/// parts of `p` (one owner per cell of dofmap's mesh), without the ghosts:
/// what a process of a distributed run needs (work O(cells' nodes), whatever
/// the number of parts). Throws Error if the sizes disagree.
DofLayout dof_numbering(const dofs::DofMap& dofmap, const Partition& p);

/// dof_numbering and every part's ghosts, with the cell pairs of `graph` (the
/// local model's diagonal graph for no bonds): the report of a partition
/// (perimorph info --partition; work O(parts × cells)). Throws Error if the
/// sizes disagree.
DofLayout dof_layout(const dofs::DofMap& dofmap, const Partition& p, const bonds::CellGraph& graph);

/// 1 for each cell with a node `owns` (a predicate on dof nodes) holds for: the
/// cells whose local block, and the cell pairs with one of them whose bonds, a
/// part computes.
template <class Owns>
std::vector<char> cells_touching(const dofs::DofMap& dofmap, Owns&& owns);

}  // namespace perimorph::partition

#include "perimorph/dofs/dof_map.hpp"

namespace perimorph::partition {

template <class Owns>
std::vector<char> cells_touching(const dofs::DofMap& dofmap, Owns&& owns) {
  std::vector<char> out(static_cast<std::size_t>(dofmap.num_cells()), 0);
  for (Index c = 0; c < dofmap.num_cells(); ++c)
    for (Index n : dofmap.cell_nodes(c))
      if (owns(n)) {
        out[static_cast<std::size_t>(c)] = 1;
        break;
      }
  return out;
}

}  // namespace perimorph::partition
