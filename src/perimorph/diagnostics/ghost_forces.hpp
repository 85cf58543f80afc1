#pragma once
// The ghost-force diagnostic (THEORY §3.2): impose u = ε̄ x on every degree of
// freedom, compute the residual r = K u at the free degrees of freedom (no
// external load), and report it per node and per unit nodal volume (the
// ghost-force density).

#include "perimorph/setup/discretization.hpp"

#include <string>
#include <vector>

namespace perimorph::diagnostics {

struct GhostForces {
  std::vector<double> residual;      ///< r = K u (dof vector), 0 on constrained dofs
  std::vector<double> nodal_volume;  ///< ∫ N_a dV per dof node (× thickness/area)
  std::vector<double> density;       ///< residual / nodal volume (dof vector)
  double max_density = 0.0;
};

/// `strain` is the symmetric tensor ε̄ (only the model's dim × dim block is used).
/// Collective: K is spread over the processes of a distributed run
/// (system::assemble_stiffness_over_processes); every process gets the whole result.
GhostForces compute_ghost_forces(const setup::Discretization& model, const Mat3& strain);

/// Writes DIR/BASENAME_ghost_forces.vtu (point data ghost_force,
/// ghost_force_density, alpha) and DIR/BASENAME_ghost_forces.csv (one row per
/// dof node: coordinates, residual, density). Returns the CSV path.
std::string write_ghost_forces(const setup::Discretization& model, const GhostForces& g,
                               const std::string& directory, const std::string& basename);

}  // namespace perimorph::diagnostics
