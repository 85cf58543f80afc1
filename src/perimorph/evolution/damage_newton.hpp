#pragma once
// Newton's method for the local damage of one increment (THEORY §6;
// [damage] solver = "newton"; docs/benchmarks/damage-solver.md): at the
// state's load factor, find u with
//
//   F(u) = A(h) u − λ b − P Σ ∫ Bᵀ (d(u) − h) C₀ ε(u) = 0,
//   d(u) = min(d_c, max(h, (Y(ε(u)) − k0)/k1))        (3.41),
//
// A(h), b the constrained system at the current damage h (non-local bonds,
// failed bonds, held dofs included), P the restriction to the free dofs.
// The Jacobian is the consistent one: A(h) − P Σ ∫ Bᵀ [(d − h) C₀ +
// (C₀ε)(C₀ε)ᵀ/k1 at the loading points] B P (fem::damage_tangent). Solved by
// PETSc SNES (la::NonlinearSolver, options prefix -damage_; default Newton
// with a line search, each step solved by GMRES preconditioned by the run's
// own preconditioner of A, e.g. the reused GAMG; -damage_ksp_type preonly
// -damage_pc_type lu for a direct solve of each step). The caller updates the
// damage from the returned u (LocalDamage), so the fixed point of the thesis
// starts at its solution and its own check ends the increment.

#include "perimorph/setup/discretization.hpp"
#include "perimorph/system/constrained_system.hpp"

#include <span>
#include <string>
#include <vector>

namespace perimorph::evolution {

struct DamageNewtonReport {
  bool converged = false;
  int steps = 0;       ///< Newton steps (= linear solves with the default direct solve)
  std::string reason;  ///< PETSc's
};

/// Solves F(u) = 0 above from `u` (in: the last solve's displacement, with
/// the prescribed values of load factor `lambda`; out: Newton's last
/// iterate). `history`: h, d at every local quadrature point.
DamageNewtonReport solve_damage_newton(const setup::Discretization& disc,
                                       const system::ConstrainedSystem& system,
                                       std::span<const double> history, double lambda,
                                       std::vector<double>& u);

}  // namespace perimorph::evolution
