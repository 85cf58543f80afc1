#pragma once
// Mechanisms inside a cell (THEORY §5). Failed bonds can leave a motion of one
// cell's nodes that no intact bond resists while the part stays connected: a
// non-local point of a DG cell whose every bond has failed, or whose intact
// bonds all lie on one line or in one plane (bond-based bonds resist only
// along ξ), e.g. after bonds between two points of one cell failed
// (intra_cell_failure = true). A is then singular although no part is cut
// free (floating_parts.hpp), and a Krylov solver breaks down (CG:
// DIVERGED_INDEFINITE_PC).
//
// Such a motion v, supported on the free dofs S of one cell, is a null vector
// of the principal block A_SS, and conversely: A is positive semi-definite, so
// vᵀ A_SS v = vᵀ A v = 0 gives A v = 0. Per cell, this takes the null space of
// A_SS (eigenvalues below 1e-10 of the largest diagonal of A before any
// downdate on S) and chooses as many of the cell's dofs as it has free modes,
// by a column-pivoted QR of the modes, so that the modes restricted to them
// are invertible: holding those dofs at zero is a statically determinate
// support, which carries no force when the applied forces do no work on the
// modes (a force that does is an error: no quasi-static equilibrium).
// Motions spread over several cells that are not cut free are not found.

#include "perimorph/la/matrix.hpp"
#include "perimorph/la/owned_dofs.hpp"
#include "perimorph/setup/discretization.hpp"

#include <functional>
#include <span>
#include <vector>

namespace perimorph::evolution {

struct CellMechanisms {
  std::size_t cells = 0;    ///< cells with at least one free mode
  std::size_t modes = 0;    ///< their free modes, = pins.size()
  std::vector<Index> pins;  ///< dofs that, held, remove the modes (sorted)
};

/// The cells to look at, in order: each one's dofs (named as the held dofs,
/// the pins and the dofs the two vectors are read at) and its centroid (for
/// a message).
struct CellsToCheck {
  std::vector<std::vector<Index>> dofs;
  std::vector<Vec3> centroid;
};

/// `cells` of `model` (each once, in the given order), their dofs `model`'s.
CellsToCheck cells_to_check(const setup::Discretization& model, std::span<const Index> cells);

/// On a piece of the model (setup::cut_to_piece), collective: the cells each
/// process lists (of `model`, the cells it decides on: setup::cells_of_process),
/// gathered in whole-mesh cell order with their dofs' names (setup::dof_name).
CellsToCheck cells_to_check_over_pieces(const setup::Discretization& model, std::span<const Index> mine);

/// The principal blocks of A over sets of dofs (named as CellsToCheck's),
/// the same on every process (collective).
using BlocksAt = std::function<std::vector<Eigen::MatrixXd>(std::span<const std::vector<Index>>)>;

/// The free modes of `cells` (each once, in the given order) in the
/// constrained matrix `A` (finalized), with `reference_diagonal` A's diagonal
/// before any downdate, leaving out the dofs of `held` (sorted: prescribed, or
/// about to be held; a pin chosen for one cell is left out of the next).
/// `force`: the applied forces at load factor 1 (empty: none). Throws Error
/// naming the cell when the forces do work on one of its free modes. With A
/// spread over processes: collective, the same arguments and result on each;
/// the two vectors are read at the cells' dofs only, a batch of cells at a
/// time (la::DofValuesAt: from their owners).
CellMechanisms find_cell_mechanisms(const setup::Discretization& model, const la::Matrix& A,
                                    const la::DofValuesAt& reference_diagonal, std::span<const Index> cells,
                                    std::span<const Index> held, const la::DofValuesAt& force);

/// The same over cells given with their dofs, A's blocks read through
/// `blocks`; held dofs, pins and the vectors' dofs named as the cells' dofs.
CellMechanisms find_cell_mechanisms(const CellsToCheck& cells, const BlocksAt& blocks,
                                    const la::DofValuesAt& reference_diagonal, std::span<const Index> held,
                                    const la::DofValuesAt& force);

}  // namespace perimorph::evolution
