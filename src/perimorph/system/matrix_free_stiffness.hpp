#pragma once
// [solver] operator = "matrix-free" (issue 16 item 3; THEORY §4): the
// stiffness of a structured grid of DG degree 0 cells with α ≡ 1 applied
// without a matrix (assembly::StructuredNonlocalOperator: one block per grid
// offset, read from the assembly of a small patch of the same grid), and the
// matrix that preconditions it: the same problem with a short horizon
// ([solver] preconditioner_horizon cell sizes, the kernel calibrated for it,
// so that its continuum limit is the same elasticity and its symbol matches
// the non-local one at low frequencies), assembled on its exact pattern.
// setup::check_matrix_free states the cases it covers.

#include "perimorph/assembly/structured_nonlocal_operator.hpp"
#include "perimorph/la/matrix.hpp"
#include "perimorph/setup/discretization.hpp"

#include <vector>

namespace perimorph::system {

struct MatrixFreeStiffness {
  assembly::StructuredNonlocalOperator K;  ///< the case's stiffness, unconstrained
  la::Matrix preconditioner;               ///< the short-horizon stiffness, unconstrained, finalized
  /// On several processes, per cell of K's window (the grid, or the box of a
  /// process's piece of the model), 1 for the cells (DG0: one node each) whose
  /// rows this process owns (preconditioner.distribution()); empty on one.
  std::vector<char> owned_cells;
};

/// Requires model.config.solver.op == matrix_free (setup::check_matrix_free
/// passed; build_discretization checks it). On several processes the cells
/// are cut by partition::coordinate_bisection and the preconditioner spread
/// over the processes as an assembled stiffness is (each row of a cell's node
/// on the cell's process). Collective.
MatrixFreeStiffness build_matrix_free_stiffness(const setup::Discretization& model);

/// The blocks per grid offset of `config`'s non-local model on a grid of
/// `layout`'s spacing: assembled on a patch of the case's grid (r + 1 cells
/// beyond the bond reach r on each side of a centre cell, nothing but the
/// material and the non-local model) and read at its centre cell.
assembly::OffsetBlocks grid_offset_blocks(const casefile::CaseConfig& config,
                                          const mesh::StructuredLayout& layout);

}  // namespace perimorph::system
