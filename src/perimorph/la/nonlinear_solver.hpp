#pragma once
// PETSc SNES wrapper: Newton's method with a line search on F(u) = 0, the
// residual and the Jacobian given as callbacks on plain arrays (so that the
// assembly that fills them needs no PETSc). Defaults: newtonls with the
// backtracking line search, a direct LU solve of each Newton step; or, given
// a LinearSolver, GMRES preconditioned by that solver's preconditioner (a
// shell PC applying it as it stands: a reused GAMG of a nearby operator costs
// no new set-up). Every PETSc option under the prefix overrides them
// (-<prefix>snes_type, -<prefix>ksp_type, -<prefix>pc_type,
// -<prefix>snes_linesearch_type, ...).

#include "perimorph/core/types.hpp"
#include "perimorph/la/linear_solver.hpp"
#include "perimorph/la/matrix.hpp"
#include "perimorph/la/node_gather.hpp"
#include "perimorph/la/owned_dofs.hpp"
#include "perimorph/la/petsc_fwd.hpp"
#include "perimorph/la/vector.hpp"

#include <exception>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace perimorph::la {

struct NonlinearReport {
  int iterations = 0;     ///< Newton steps
  int linear_solves = 0;  ///< linear solves (one per step for a direct solve)
  int residual_evaluations = 0;
  bool converged = false;
  std::string reason;  ///< PETSc's converged/diverged reason
  double residual_norm = 0.0;
};

class NonlinearSolver {
 public:
  /// r = F(u): u whole-length in the assembly's numbering (on several
  /// processes, exact at the dofs read_only names, NaN elsewhere), r at the
  /// dofs this process owns (owned_dofs(), in its order; on one process every
  /// dof: r whole).
  using Residual = std::function<void(std::span<const double> u, std::span<double> r)>;
  /// J = ∂F/∂u at u: J is zeroed before the call; add into it (Matrix::add),
  /// the solver finalizes it after.
  using Jacobian = std::function<void(std::span<const double> u, Matrix& J)>;

  /// `J` (its pattern holds every entry the Jacobian adds) is owned by the
  /// caller and outlives the solver. Convergence: ||F|| ≤ max(atol, rtol ||F(u₀)||)
  /// within max_iterations steps. `preconditioner` (optional, outlives the
  /// solver): the Newton steps are solved by GMRES with its preconditioner.
  NonlinearSolver(Matrix& J, Residual residual, Jacobian jacobian, double rtol, double atol,
                  int max_iterations, const std::string& options_prefix,
                  const LinearSolver* preconditioner = nullptr);
  ~NonlinearSolver();
  NonlinearSolver(const NonlinearSolver&) = delete;
  NonlinearSolver& operator=(const NonlinearSolver&) = delete;

  /// On several processes, the callbacks get u at these dof nodes (of
  /// `block_size` entries) only (assembly numbering; NaN at the others: what
  /// this process's rows read, setup::nodes_read) instead of whole. Nothing
  /// changes on one process.
  void read_only(std::vector<Index> nodes, int block_size);
  /// The dofs whose entries of r the residual callback writes.
  const OwnedDofs& owned_dofs() const { return owned_; }
  /// Solves F(u) = 0 from u (the initial guess in, the last iterate out).
  /// Never throws for non-convergence: the report says how it ended. Stops
  /// early (not converged, reason STAGNATED) when ||F|| fell by less than
  /// 10 % in each of two consecutive steps.
  NonlinearReport solve(Vector& u);

  // For the PETSc callbacks (la/nonlinear_solver.cpp): F and J at u. On
  // several processes (a distributed J), u is gathered whole for the
  // callbacks (or at read_only's nodes; assembly numbering) and r is set from
  // the owned entries they compute.
  void evaluate_residual(PetscVecHandle u, PetscVecHandle r);
  void evaluate_jacobian(PetscVecHandle u);
  std::exception_ptr callback_error;  ///< thrown in a callback, rethrown by solve
  int residual_evaluations = 0;
  std::vector<double> residual_norms;  ///< ||F|| after each step of the current solve
  bool stagnated = false;

 private:
  PetscSnesHandle snes_ = nullptr;
  Matrix& J_;
  Residual residual_;
  Jacobian jacobian_;
  Vector r_;
  OwnedDofs owned_;                  ///< J's owned rows
  Vector u_whole_, r_whole_;         ///< scratch of a distributed solve (J's layout)
  std::optional<NodeGather> reads_;  ///< read_only's nodes (empty: u whole)
  /// u as the callbacks get it (distributed J).
  std::vector<double> gathered(PetscVecHandle u);
};

}  // namespace perimorph::la
