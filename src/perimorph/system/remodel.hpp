#pragma once
// A constrained system carried over to a grown α (THEORY §5, adaptive zone):
// the mesh stays, α grew, some cells switched from CG to DG (more dofs), the
// stiffness changed in the cells α reached and in the horizons around them.
// The new K is the old one with those cells' stiffness subtracted, its
// entries renumbered onto the new dofs, and the new stiffness of those cells
// added: the non-local assembly, which dominates the cost, runs over the
// changed cells only. Copying and constraining K is O(non-zeros).

#include "perimorph/setup/boundary_conditions.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/system/constrained_system.hpp"

#include <memory>
#include <span>
#include <vector>

namespace perimorph::bonds {
class BrokenBonds;
}

namespace perimorph::system {

/// The cells whose stiffness differs between two discretizations of one
/// mesh that differ in α: α at one of its non-local points, C at one of its
/// local points (the horizon integral of the morphing reaches δ beyond α's
/// change), or its continuity (CG → DG). Sorted.
std::vector<Index> changed_cells(const setup::Discretization& before, const setup::Discretization& after);

/// A dof vector of `before` carried to `after` (same mesh, or two pieces of
/// it, setup::cut_to_piece): every dof node of
/// a cell takes the value of the same corner of that cell before, so a DG
/// copy of a CG node takes the CG value and a continuous displacement stays
/// exactly the same field. A DG degree 0 node takes the Q1 value at the
/// centroid (the mean of the corners); a corner node made from a DG degree 0
/// cell takes the cell's value. `combine` = max: where several old values
/// meet in one new node (a node two DG cells share again), their maximum;
/// otherwise the last cell's value (a continuous field agrees). On pieces the
/// cells of `after` that `before` lacks carry nothing (their new nodes keep 0,
/// or −∞ with max): a node's value is the whole model's where `before` holds
/// every cell using it with its values, as for the nodes `after`'s process owns
/// when `after`'s piece grew from `before`'s (rebuild_piece_for_alpha: the cells
/// using an owned node are its part's node neighbours, in both pieces).
std::vector<double> transfer_dof_vector(const setup::Discretization& before,
                                        const setup::Discretization& after, std::span<const double> values,
                                        bool combine_max = false);

/// Seconds spent in each step of remodel (for the run's report).
struct RemodelTimes {
  double subtract = 0.0;   ///< old stiffness of the changed cells off the old K
  double copy = 0.0;       ///< new pattern, old entries renumbered into it
  double add = 0.0;        ///< new stiffness of the changed cells
  double constrain = 0.0;  ///< Dirichlet elimination, reference diagonal
};

struct Remodelled {
  std::unique_ptr<ConstrainedSystem> system;  ///< on `after`, solver not attached
  std::vector<Index> cells;                   ///< changed_cells(before, after); empty when distributed
  /// The partial update was used (false: the changed cells' bond pairs, in
  /// the old model and the new, outnumbered the new model's: assembled anew).
  bool partial = true;
  RemodelTimes times;
};

/// The constrained system of `after` from `system` (on `before`), `failed`
/// bonds left out of both (they are out of system's K already). `system`'s K
/// is consumed (the changed cells' stiffness is subtracted from it). `bc` and
/// `F` are `after`'s constraints and loads (setup/boundary_conditions.hpp).
/// The reference diagonal (ConstrainedSystem::without_stiffness) carries over
/// through transfer_dof_vector (max). The result equals a system assembled
/// from `after` with `failed` left out, to round-off. Subtracting and adding
/// costs about twice the assembly of the changed cells' bond pairs: when
/// those (old and new) outnumber the new model's pairs, the new model is
/// assembled instead (Remodelled::partial false), so the update never costs
/// much more than an assembly; spread over processes (K with a
/// la::Distribution), the new model is always assembled, over the processes.
/// `damage` (d at every local quadrature point,
/// THEORY §6; empty: none) lowers the local stiffness of both models alike.
Remodelled remodel(ConstrainedSystem& system, const setup::Discretization& before,
                   const setup::Discretization& after, const bonds::BrokenBonds* failed,
                   setup::DirichletData bc, std::span<const double> F, std::span<const double> damage = {});

/// The constrained system of `after`, a process's piece of the model rebuilt
/// for a grown α (setup::rebuild_piece_for_alpha), from `system` on the piece
/// `before`: assembled anew over the processes, as remodel does spread over
/// processes (so the same bits as a run on parts), `failed` and `damage` in
/// after's numbers. The reference diagonal carries over as in remodel, from
/// `reference`, system's at every dof of `before` that its process reads
/// (its owners' at the halo), through transfer_dof_vector on the pieces.
/// Collective.
Remodelled remodel_piece(const setup::Discretization& before, std::span<const double> reference,
                         const setup::Discretization& after, const bonds::BrokenBonds* failed,
                         setup::DirichletData bc, std::span<const double> F,
                         std::span<const double> damage = {});

}  // namespace perimorph::system
