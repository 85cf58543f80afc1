#pragma once
// A run's state carried from its piece of the model to the next piece, the
// one rebuilt for a grown α (setup::rebuild_piece_for_alpha; THEORY §5), by
// neighbour exchanges alone (issue 17, item 2): the next piece holds its
// part's cells again and a halo that grew with α's bonds, so what it lacks
// is the state of the cells new to its halo, which their parts' processes
// hold. Nothing of the whole model is gathered (until 2026-12-07 the state
// went whole to every process, run::WholeState).

#include "perimorph/evolution/run_state.hpp"

namespace perimorph::setup {
struct Discretization;
}

namespace perimorph::run {

/// `state`, the run's on piece `before`, on piece `after` (its successor: the
/// same parts, every cell of `before` in it): the failed bonds whose two cells
/// `after` holds, with their places in the whole order of failure, in that
/// order (those a cell new to the piece has come from the process of the part
/// that decided them); D of the part's cells; the damage history of every
/// cell of `after` (a new cell's from the process of its part); the
/// counters, α, load and ledger as they are. u is left zero and the held
/// dofs empty (held anew on the next system, PartSupport::rebind): u goes
/// across with transfer_dof_vector at the owned dofs, then from the owners.
/// Collective over PETSC_COMM_WORLD; the same bits as the state gathered
/// whole and cut to `after` (run::WholeState::piece_of).
evolution::RunState next_piece_state(const setup::Discretization& before, const setup::Discretization& after,
                                     const evolution::RunState& state);

}  // namespace perimorph::run
