#pragma once
// The hybrid stiffness K = K_local(C(x)) + K_nl of a model (THEORY §4),
// assembled into a PETSc matrix with exact preallocation.

#include "perimorph/assembly/nonlocal_assembly.hpp"
#include "perimorph/la/matrix.hpp"
#include "perimorph/setup/discretization.hpp"

#include <span>

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

}  // namespace perimorph::system
