#pragma once
// The state of a run on a piece of the model (setup::cut_to_piece) in the
// whole model's numbers, as a run on one process holds it, and back: what a
// checkpoint of a run on pieces writes and reads (run/checkpoint.hpp), so that
// a checkpoint continues on parts or pieces, on any number of processes.
//
// A piece holds the failed bonds whose two cells it holds, each with its place
// in the whole model's order of failure (RunState::failed_place); every failed
// bond is held by the process that decided it (the cells bonded to its part's
// are in its piece). Its dissipation per cell is the whole model's on the
// cells of its part (all their bonds are held, added in the same order), and
// its held dofs are dof names (setup::dof_name), every process's alike. Its
// damage history is every cell's of its piece, each cell's updated alike on
// every process that holds it (evolution::LocalDamage).
// Every function is collective over PETSC_COMM_WORLD and O(whole model) on
// each process that receives the whole lists: process 0 alone for a
// checkpoint, which it writes (la::Onto::process_zero; the others send their
// share), every process for a restart (each cuts its piece from them). A
// rebuild for a grown α carries the state by neighbour exchange instead
// (run/next_piece_state.hpp).

#include "perimorph/core/types.hpp"
#include "perimorph/evolution/run_state.hpp"
#include "perimorph/la/neighbour_exchange.hpp"
#include "perimorph/system/whole_numbering.hpp"

#include <span>
#include <utility>
#include <vector>

namespace perimorph::setup {
struct Discretization;
}

namespace perimorph::run {

class WholeState {
 public:
  /// For a piece of the model (Discretization::piece set); whole() gathers
  /// onto `onto`, piece_of needs la::Onto::every_process.
  explicit WholeState(const setup::Discretization& piece, la::Onto onto = la::Onto::every_process);

  const system::WholeNumbering& numbering() const { return numbering_; }
  /// The whole mesh's cell count.
  Index cells() const { return cells_; }

  /// `state` (the piece's) in the whole model's numbers: u from `owned_u`
  /// (its values at the owned dofs, la::OwnedDofs order), the failed bonds in
  /// the whole order of failure, D of every cell, the held dofs as whole
  /// dofs, the damage history of every cell. The BrokenBonds set is left
  /// empty (a checkpoint writes the ordered list). On a process that does
  /// not receive (la::receives), u, the failed bonds, D, the held dofs and
  /// the history are empty and the cell count is 0.
  evolution::RunState whole(const evolution::RunState& state, std::span<const double> owned_u) const;
  /// An initial state of the whole model, for evolution::restore_state to
  /// read a checkpoint's into (u, D per cell, the failed-bond set and the
  /// damage history sized for the whole model).
  evolution::RunState empty_whole() const;
  /// The piece's part of a whole state: u at the piece's dofs, the failed
  /// bonds whose two cells the piece holds (with their places), D of its
  /// part's cells (the only ones it reads), the held dofs as names, the
  /// damage history of its cells.
  evolution::RunState piece_of(const evolution::RunState& whole) const;

 private:
  std::size_t points_per_cell() const;  ///< of the damage history (0 without damage)

  const setup::Discretization* piece_;
  la::Onto onto_;
  system::WholeNumbering numbering_;
  Index cells_ = 0;
};

}  // namespace perimorph::run
