#pragma once
// Cells distributed over ranks (issue 17, item 1): an owner per cell, and the
// halo each rank needs: the cells of other ranks that share a node with an
// owned cell (CG dofs, local assembly) or interact non-locally with one (a pair
// of the cell graph: bonds, THEORY §4). Serial for now: every rank holds the
// whole mesh and computes the same partition; the halo sizes measure what a
// distributed run would exchange.

#include "perimorph/core/types.hpp"

#include <span>
#include <string>
#include <vector>

namespace perimorph::mesh {
class Mesh;
}
namespace perimorph::bonds {
struct CellGraph;
}

namespace perimorph::partition {

/// An owner (0 … parts − 1) per cell.
struct Partition {
  int parts = 1;
  std::vector<int> owner;
};

/// Recursive coordinate bisection of the cell centroids: a set of cells for
/// q parts is cut across the longest extent of its centroids' bounding box
/// into ⌊q/2⌋ and ⌈q/2⌉ parts, the first getting the cells with the smallest
/// coordinates in proportion (ties broken by cell index, so the result does not
/// depend on the sort). Part sizes differ by at most one cell per level.
/// Throws InputError if parts < 1 or parts > cells.
Partition coordinate_bisection(const mesh::Mesh& mesh, int parts);

/// The cells of part `part` of coordinate_bisection(mesh, parts), marked 1
/// (empty for one part): the cells a process of a distributed run visits in
/// a pass that visits each cell once over all processes (the stretch pass,
/// the damage update).
std::vector<char> cells_of_part(const mesh::Mesh& mesh, int parts, int part);

/// The cells of part `part` and every cell sharing a mesh node with one of
/// them, marked 1 (empty for one part): a superset of the cells with a dof
/// node the part can own, whatever α makes CG or DG (dof_numbering: a DG node
/// is its cell's part's, a CG node, at a mesh node, the lowest part among
/// its cells'), so of the cells whose local stiffness the part assembles
/// (cells_touching) and of its cells_of_part. What a process of a distributed
/// run computes the morphed C of (setup::Discretization::computed_cells).
std::vector<char> cells_near_part(const mesh::Mesh& mesh, int parts, int part);

/// The same for the parts `owner` (one per cell of `mesh`) gives: on a window
/// of a mesh (setup::MeshWindow), those of the window's cells.
std::vector<char> cells_near_part(const mesh::Mesh& mesh, std::span<const int> owner, int part);

/// The cells each cell is coupled to: those sharing a node with it (CG dofs,
/// local assembly) and its neighbours in `graph` (bonds), the cell itself
/// included; rows sorted. The graph a partitioner should cut least.
bonds::CellGraph coupling_graph(const mesh::Mesh& mesh, const bonds::CellGraph& graph);

/// What each part owns and needs from the others.
struct HaloStats {
  std::vector<Index> owned;     ///< cells owned, per part
  std::vector<Index> ghosts;    ///< halo cells (owned by another part), per part
  std::vector<int> neighbours;  ///< parts that own a halo cell, per part
  std::size_t cut_pairs = 0;    ///< coupled pairs (E < F) whose ends have two owners
  std::size_t pairs = 0;        ///< coupled pairs (E < F)
  Index max_owned() const;
  Index max_ghosts() const;
  /// Σ ghosts / Σ owned: the halo's share of the cells a rank holds.
  double ghost_ratio() const;
};

/// The halo of every part of `p`: for each part, the cells of other parts
/// coupled to an owned cell (`coupling`: coupling_graph).
HaloStats halo(const bonds::CellGraph& coupling, const Partition& p);

}  // namespace perimorph::partition
