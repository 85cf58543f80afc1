#pragma once
// What a process decides about the dof nodes of its piece of the model alone
// (issue 17, item 1): which it owns, and a key naming each node the same way
// on every process, whose order is the whole model's dof order. The
// distributed numbers follow from these with one prefix sum and one exchange
// of the ghosts' numbers by key (system::piece_distribution), with no array
// as long as the whole model's.
//
// Keys: a CG node is named by its global mesh node n (key n); a DG node by its
// global cell c and corner a (key N + c k + a, N the whole mesh's nodes, k its
// nodes a cell; a DG degree 0 node has a = 0). The whole model's dof map
// (dofs::DofMap) numbers the CG nodes in mesh order, then the DG nodes cell
// by cell, corner by corner: its order is the keys' order, so numbering a
// part's owned nodes in key order gives partition::dof_numbering's numbers.

#include "perimorph/core/types.hpp"

#include <span>
#include <vector>

namespace perimorph::dofs {
class DofMap;
}
namespace perimorph::mesh {
struct PartMesh;
}

namespace perimorph::partition {

struct PieceDofs {
  /// 1 for each local dof node this process owns.
  std::vector<char> owned;
  /// Each local dof node's key, ascending in local order.
  std::vector<Index> key;
  /// Keys lie in [0, key_space), the same on every process.
  Index key_space = 0;

  Index num_owned() const;
};

/// The keys and owners of the dof nodes of `local`, a dof map built on
/// `piece` (each local cell's continuity the whole model's), with
/// `cell_owner` the owning part of each local cell; `whole_nodes` and
/// `whole_cells` are the whole mesh's counts. A node belongs to the lowest
/// part among the cells using it (partition::dof_numbering's rule); the piece
/// decides that alone for the nodes of its own cells (those of part `part`)
/// when it holds every cell sharing a mesh node with one of them
/// (cells_near_part), which is what it needs: a node no cell of the part uses
/// is not the part's. Throws Error if the keys overflow Index, or a size
/// disagrees.
PieceDofs piece_dofs(const dofs::DofMap& local, const mesh::PartMesh& piece, std::span<const int> cell_owner,
                     int part, Index whole_nodes, Index whole_cells);

}  // namespace perimorph::partition
