#pragma once
// A process's piece of a model (issue 17, item 1): the discretization of a
// part (build_discretization with a ModelPart) cut to the cells the process
// reads — those whose morphed C it computes (its part and their node
// neighbours) and those whose non-local points it stores (every cell its
// bonds reach; with the matrix-free operator, whose cell graph holds no bond,
// the cells of its reach) — as a model of its own, numbered locally in the global
// order, with the global number of each cell and node, the part of each
// cell and the keys and owners of its dof nodes (partition::piece_dofs), from
// which system::piece_distribution numbers them. Assembled on its
// distribution, the piece gives the whole model's matrix rows, bit for bit.

#include "perimorph/partition/piece_dofs.hpp"
#include "perimorph/setup/discretization.hpp"

#include <functional>
#include <memory>
#include <span>
#include <vector>

namespace perimorph::setup {

/// What a piece's local numbers are in the whole model (Discretization::piece).
struct PieceNumbers {
  /// The global number of each local cell and mesh node, ascending.
  std::vector<Index> global_cell, global_node;
  /// The part of each local cell; the piece's process's part is `part`.
  std::vector<int> owner;
  int part = 0;
  /// What the piece decides about its dof nodes (owners and keys).
  partition::PieceDofs dofs;
  /// The local number of global cell c, or -1 if the piece lacks it (a search).
  Index local_cell(Index c) const;
  /// Whether local cell c is of the piece's process's part (the process
  /// decides on it and writes it).
  bool of_part(Index c) const { return owner[static_cast<std::size_t>(c)] == part; }
  /// The cells of the part.
  Index part_cells() const;
};

/// What a piece of a run with [adaptivity] is cut from (Discretization::source).
struct PieceSource {
  /// The process's part (build_discretization with a ModelPart, share_flags
  /// kept) without what a rebuild for α makes anew: its morphed C, non-local
  /// points, cell graph, cuts and CG/DG flags are empty (keep_source). Its
  /// mesh and dof map number the state carried across a rebuild.
  Discretization part;
  std::vector<int> owner;  ///< the part of every cell of the part's mesh (whole, or its window)
};

/// The source of the pieces of a run with [adaptivity]: `part` less the
/// arrays rebuild_for_alpha computes anew (as large as the piece's own),
/// with `owner`, the part of every cell of its mesh (the whole mesh, or its
/// window: Discretization::window).
std::shared_ptr<const PieceSource> keep_source(Discretization part, std::vector<int> owner);

/// The whole-mesh number of cell c of `disc` (c itself but on a piece), and back
/// (-1 where a piece lacks it).
Index global_cell(const Discretization& disc, Index c);
Index local_cell(const Discretization& disc, Index global);

/// A name for dof `dof` of `disc` that every process gives it alike, for
/// lists of dofs gathered over the processes: the dof itself on a part or the
/// whole model; on a piece key × dim + component, its node's key
/// (partition::PieceDofs: names sort as the whole model's dofs do). And back:
/// the dof of a name, -1 where a piece lacks it (a search).
Index dof_name(const Discretization& disc, Index dof);
Index dof_of_name(const Discretization& disc, Index name);

/// The piece of `part` (built for part `part_number`, or the whole model)
/// that its process reads, in local numbers: its mesh (a mesh::PartMesh's,
/// with the box layout kept), dof map, morphed C, non-local points and cell
/// graph (the rows of the computed cells), flags, damage laws, computed
/// cells, and `piece` (PieceNumbers). No share_flags: a rebuild for a grown
/// α is not made on a piece. A part built on a window (Discretization::window)
/// gives a piece in the whole mesh's numbers; Error if a cell it reads lies on
/// a side where the window cuts the grid (the window would be too narrow).
/// `owner` is the part of every cell of the part's
/// mesh and `any_over_processes` whether a condition holds on any process
/// (collective; la::), kept in the piece's discretization
/// (Discretization::any_over_processes). Requires the part's computed cells
/// to be its part's node neighbours (build_discretization's, cells_near_part).
Discretization cut_to_piece(const Discretization& part, std::span<const int> owner, int part_number,
                            std::function<bool(bool)> any_over_processes);

/// The piece of `piece`'s process for α replaced by `alpha` (THEORY §5: α
/// grows during a run): its source part rebuilt (rebuild_for_alpha, collective:
/// the parts share their CG/DG flags) and cut anew (cut_to_piece), with the
/// same parts. Its halo grows with α (the bonds of the cells α reached reach
/// further). The new part is kept as the new piece's source. Requires a piece
/// with a source (Discretization::source).
Discretization rebuild_piece_for_alpha(const Discretization& piece, alpha::AlphaField alpha);

/// The cells of `disc` this process decides on (bond failure, damage,
/// adaptive α, floating parts) and writes, marked 1: on a piece those of its
/// part (PieceNumbers), on a part of `processes` > 1 its cells of
/// partition::coordinate_bisection (part `process`), on one process none
/// marked and the vector empty (every cell).
std::vector<char> cells_of_process(const Discretization& disc, int processes, int process);

}  // namespace perimorph::setup
