#pragma once
// Discrete calibration (issue 3, item 7): the bulk tensor of the non-local
// model summed with the actual quadrature,
//   D(x_g) = Σ_h w_h c(ξ) ξ⊗ξ⊗ξ⊗ξ / (2|ξ|²)   (complete horizon),
// differs from the continuum C₀ by the quadrature error of the horizon
// integral (docs/verification/quadrature-energy.md). The factor returned
// scales ĉ so that the cell average of D matches C₀ in the least-squares
// sense: factor = (C₀ : D̄) / (D̄ : D̄), Voigt entries.

#include "perimorph/mesh/mesh.hpp"
#include "perimorph/peridynamics/micromodulus.hpp"

#include <Eigen/Core>

namespace perimorph::assembly {

/// D̄ (Voigt, model dimension) averaged over the points of one cell of the
/// infinite lattice of `layout`'s cells with n Gauss points per direction,
/// with the plain cut-off or the partial-volume bond rule.
Eigen::MatrixXd lattice_bulk_tensor(const mesh::StructuredLayout& layout, int dim, int n,
                                    const peridynamics::Micromodulus& kernel, bool partial_volume = false);

/// The least-squares factor that maps D̄ onto C₀.
double discrete_calibration_factor(const mesh::StructuredLayout& layout, int dim, int n,
                                   const peridynamics::Micromodulus& kernel, const Eigen::MatrixXd& C0,
                                   bool partial_volume = false);

}  // namespace perimorph::assembly
