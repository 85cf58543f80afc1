#pragma once
// The hybrid stiffness K = K_local(C(x)) + K_nl of a model (THEORY §4),
// assembled into a PETSc matrix with exact preallocation.

#include "perimorph/assembly/nonlocal_assembly.hpp"
#include "perimorph/la/distribution.hpp"
#include "perimorph/la/matrix.hpp"
#include "perimorph/setup/discretization.hpp"

#include <memory>
#include <span>

namespace perimorph::partition {
struct DofLayout;
}

namespace perimorph::system {

struct AssembledStiffness {
  la::Matrix K;
  assembly::NonlocalStats nonlocal;  ///< zero for a purely local model
  double local_seconds = 0.0, nonlocal_seconds = 0.0, setup_seconds = 0.0;
};

/// Assembles K (unconstrained, finalized), failed bonds (if given) left out;
/// with `damage` (d at every local quadrature point, THEORY §6; empty: d = 0)
/// the local stiffness is the damaged one (setup::damaged_stiffness).
AssembledStiffness assemble_stiffness(const setup::Discretization& model,
                                      const bonds::BrokenBonds* broken = nullptr,
                                      std::span<const double> damage = {});

/// The distribution of part `part` of `layout` (this process's, for part =
/// its rank) for la::Matrix and la::Vector.
std::shared_ptr<const la::Distribution> distribution_of(const partition::DofLayout& layout, int part);

/// The same spread over the processes of PETSC_COMM_WORLD by `distribution`
/// (distribution_of; issue 17): this process computes the cells and cell
/// pairs that touch the nodes it owns and keeps their rows
/// (partition/dof_layout.hpp, "owner computes"), so K is the serial matrix bit
/// for bit and no entry travels. Collective.
AssembledStiffness assemble_stiffness(const setup::Discretization& model,
                                      const std::shared_ptr<const la::Distribution>& distribution,
                                      const bonds::BrokenBonds* broken = nullptr,
                                      std::span<const double> damage = {});

/// This process's share of the dof nodes of `model` on PETSC_COMM_WORLD: the
/// cells cut into one part per process by partition::coordinate_bisection,
/// the nodes owned and numbered by partition::dof_numbering; null on one
/// process.
std::shared_ptr<const la::Distribution> distribution_over_processes(const setup::Discretization& model);

/// K spread over the processes of PETSC_COMM_WORLD: the cells cut into one
/// part per process by partition::coordinate_bisection, the dofs laid out by
/// partition::dof_numbering. On one process, assemble_stiffness(model, broken,
/// damage). Collective.
AssembledStiffness assemble_stiffness_over_processes(const setup::Discretization& model,
                                                     const bonds::BrokenBonds* broken = nullptr,
                                                     std::span<const double> damage = {});

}  // namespace perimorph::system
