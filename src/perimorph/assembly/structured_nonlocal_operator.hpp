#pragma once
// The non-local operator of a structured grid applied without a matrix
// (THEORY §4; issue 16 item 3). On a structured box of cells with one
// non-local point each (DG degree 0), α ≡ 1, no cut and no failed bond, the
// bond between cells i and i + o depends only on the offset o: the stiffness
// is K_ii = Σ_o B_o, K_{i,i+o} = −B_o over the neighbours inside the grid,
// with one dim × dim block B_o per offset. So
//     (K x)_i = Σ_o B_o (x_i − x_{i+o}),
// which needs the blocks (a few kB) instead of the matrix (GBs at 10⁵ cells).
// The blocks are read from the assembly of a small model with the same
// spacing, horizon and kernel, so the product equals the assembled one to
// round-off. Each row is summed in the same offset order by whichever thread
// owns it: bit-identical for any thread count.

#include "perimorph/assembly/nonlocal_assembly.hpp"
#include "perimorph/assembly/sparsity.hpp"

#include <array>
#include <span>
#include <vector>

namespace perimorph::assembly {

/// Per grid offset o ≠ 0 with a bond: B_o = −K(c, c + o) (dim × dim, row-major).
struct OffsetBlocks {
  int dim = 3;
  std::vector<std::array<int, 3>> offsets;
  std::vector<double> blocks;  ///< dim² per offset
};

/// The blocks of the cell `centre` of a structured DG0 space with α ≡ 1
/// (every offset in the horizon must fit inside the grid around it; throws
/// Error otherwise, or when the space is not structured DG0).
OffsetBlocks offset_blocks(const NonlocalSpace& space, Index centre);

/// A box of a grid's cells: its lowest cell (i, j, k) and its extent. A
/// window's cell c (window-local) is i + w0 (j + w1 k).
struct GridWindow {
  std::array<Index, 3> lo{0, 0, 0};
  std::array<Index, 3> size{1, 1, 1};
  Index count() const { return size[0] * size[1] * size[2]; }
};

class StructuredNonlocalOperator {
 public:
  /// `cells`: the grid (n0, n1, n2); `node_of_cell[c]`, c = i + n0 (j + n1 k):
  /// the dof node of each cell (dofs node · dim + d).
  StructuredNonlocalOperator(OffsetBlocks blocks, std::array<Index, 3> cells,
                             std::vector<Index> node_of_cell);
  /// On a window of the grid `cells` (a process's piece of the model, issue
  /// 17): `node_of_cell[c]` for each window cell c, −1 where the piece has no
  /// cell. The flags of the methods below are then per window cell, and a
  /// flagged cell's neighbours at the offsets must be in the window and the
  /// piece (nodes_read checks it).
  StructuredNonlocalOperator(OffsetBlocks blocks, std::array<Index, 3> cells, GridWindow window,
                             std::vector<Index> node_of_cell);
  /// y ← K x (length: the dof nodes · dim). OpenMP over cells. With `cells`
  /// (one flag per cell), only the rows of the flagged cells are written (a
  /// process's own rows; x must hold the values of every cell they read).
  void apply(std::span<const double> x, std::span<double> y, std::span<const char> cells = {}) const;
  std::size_t offsets() const { return b_.offsets.size(); }
  /// The dof nodes whose values apply(x, y, cells) reads: those of the
  /// flagged cells and of their neighbours at the offsets (a process's halo
  /// of the bond reach), ascending. Throws Error if one is not in the window
  /// or the piece.
  std::vector<Index> nodes_read(std::span<const char> cells) const;
  /// The pattern of K: each cell with itself and its neighbours at the
  /// offsets (block size dim), exact for the bonds (the cell graph's pattern
  /// holds every pair of cells within the horizon of each other's boxes).
  /// With `cells`, the rows of the flagged cells only, the others empty.
  SparsityPattern sparsity(std::span<const char> cells = {}) const;
  /// K += the operator, one block row per cell (for a preconditioner built on
  /// a short horizon's blocks: la::Matrix needs entries); with `cells`, the
  /// rows of the flagged cells only (a process's own).
  void assemble(MatrixInserter& K, std::span<const char> cells = {}) const;

 private:
  /// Calls visit(q, neighbour) for every offset q whose neighbour of window
  /// cell c lies inside the grid, in offset order (window cell numbers).
  template <class Visit>
  void for_each_neighbour(Index c, Visit&& visit) const;

  OffsetBlocks b_;
  std::array<Index, 3> n_;
  GridWindow w_;
  std::vector<Index> node_;
  Index nodes_ = 0;  ///< dof nodes: the largest of node_ plus one
};

}  // namespace perimorph::assembly
