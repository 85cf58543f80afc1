#pragma once
// The linear system of a run (THEORY §4–5): K, unconstrained (reactions,
// energies and work read it); A, K with the prescribed dofs eliminated
// (symmetric positive definite); rhs_unit, the right-hand side at load factor
// 1 (the applied forces, and the prescribed values moved over); the Dirichlet
// data; and the solver on A. The load enters linearly: the system at load
// factor λ is A u = λ rhs_unit. Bond failure changes K, A and rhs_unit in
// place (BondFailure::apply) and then calls operator_changed().

#include "perimorph/driver/boundary_conditions.hpp"
#include "perimorph/driver/model.hpp"
#include "perimorph/la/linear_solver.hpp"
#include "perimorph/la/matrix.hpp"
#include "perimorph/la/vector.hpp"

#include <memory>
#include <span>

namespace perimorph::driver {

class ConstrainedSystem {
 public:
  /// Constrains `K` (assembled, finalized) by `bc`, with the external force
  /// `F` at load factor 1. No solver yet (attach_solver).
  ConstrainedSystem(const Model& model, la::Matrix K, DirichletData bc, std::span<const double> F);

  /// The case's solver ([solver] rtol, max_iterations; PETSc options from the
  /// options database) on A, with the rigid-body near-null space of the nodes.
  void attach_solver();
  /// Solves A u = λ rhs_unit (u: the initial guess in, the solution out).
  /// Throws SolverError (la::LinearSolver). Requires attach_solver.
  la::SolveReport solve(double lambda, la::Vector& u);
  /// A has changed (a downdate or held dofs): the solver takes it again.
  void operator_changed();

  la::Matrix& K() { return K_; }
  const la::Matrix& K() const { return K_; }
  la::Matrix& A() { return A_; }
  const la::Matrix& A() const { return A_; }
  la::Vector& rhs_unit() { return rhs_unit_; }
  const la::Vector& rhs_unit() const { return rhs_unit_; }
  const DirichletData& bc() const { return bc_; }

 private:
  const Model& model_;
  la::Matrix K_, A_;
  DirichletData bc_;
  la::Vector rhs_unit_, rhs_;
  std::unique_ptr<la::LinearSolver> solver_;
};

}  // namespace perimorph::driver
