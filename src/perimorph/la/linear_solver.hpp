#pragma once
// PETSc KSP/PC wrapper. Default: conjugate gradients with GAMG preconditioning
// and the rigid-body near-null space (THEORY §4, "Solver"); every PETSc option
// from the case file or the command line overrides it (-ksp_type preonly
// -pc_type cholesky for a direct solve). Solves are warm-started from x.

#include "perimorph/core/types.hpp"
#include "perimorph/la/matrix.hpp"
#include "perimorph/la/shell_matrix.hpp"
#include "perimorph/la/vector.hpp"

#include <functional>
#include <span>
#include <string>

namespace perimorph::la {

struct SolveReport {
  int iterations = 0;
  double relative_residual = 0.0;  ///< ||b − A x|| / ||b|| (true residual)
  std::string reason;              ///< PETSc's converged/diverged reason
  std::string ksp_type, pc_type;
  /// the reused preconditioner was rebuilt for this solve (it failed, or the
  /// iterations had grown: LinearSolver::solve)
  bool rebuilt_preconditioner = false;
  /// solved by the direct fallback (LinearSolver::allow_direct_fallback)
  bool direct_fallback = false;
  /// null pivots MUMPS found and held in that direct solve (−1: none made)
  int null_pivots = -1;
};

/// The coordinate of a dof node (assembly numbering), for the rigid-body
/// near-null space; asked only at the nodes this process owns.
using NodeCoordinate = std::function<Vec3(Index node)>;

class LinearSolver {
 public:
  LinearSolver(double rtol, int max_iterations);
  ~LinearSolver();
  LinearSolver(const LinearSolver&) = delete;
  LinearSolver& operator=(const LinearSolver&) = delete;

  /// Sets the operator (and preconditioner matrix). Call again after the
  /// matrix values change; the near-null space is attached to A.
  void set_operator(Matrix& A, const NodeCoordinate& node_coordinate, int dim);
  /// A matrix-free operator A, preconditioned from the assembled matrix P
  /// (KSPSetOperators(A, P): GAMG, Jacobi … are built on P, which carries the
  /// near-null space). Both are kept alive by the caller.
  void set_operators(const ShellMatrix& A, Matrix& P, const NodeCoordinate& node_coordinate, int dim);
  /// Solves A x = b starting from x. With -ksp_reuse_preconditioner, the
  /// preconditioner is rebuilt for the present matrix before a solve when the
  /// last one needed more than 2 n + 10 iterations, n those of the first
  /// solve after the last build, and a solve that diverges is retried once
  /// with it rebuilt (both reported in SolveReport); a direct solve
  /// (-ksp_type preonly) with a kept factor counts as diverged when its true
  /// relative residual exceeds rtol (the factor is of an earlier matrix). Throws SolverError on
  /// divergence or a non-finite solution, naming PETSc's reason and the
  /// options to try.
  SolveReport solve(const Vector& b, Vector& x);

  /// After bond failures the matrix can be singular through mechanisms that
  /// the supports do not find (a fragment hanging by collinear bonds); a
  /// Krylov solve then breaks down. With the fallback allowed, a Krylov solve
  /// that fails (also with a rebuilt preconditioner) is redone by a direct
  /// solve (MUMPS LU, options prefix `fallback_`) that detects null
  /// pivots (ICNTL(24) = 1, relative threshold CNTL(3) = 1e-10) and holds
  /// them: for a consistent right-hand side, the mechanism's loads being in
  /// balance, that is a solution with the free motions at rest. It is accepted
  /// when its true relative residual is ≤ max(10 rtol, 1e-9), else
  /// SolverError; every later solve is then direct. Only for set_operator
  /// (a matrix with entries). Off by default: a singular matrix from missing
  /// supports must remain an error.
  void allow_direct_fallback(bool allow) { fallback_allowed_ = allow; }
  /// Whether solves are now made by the direct fallback.
  bool direct() const { return direct_ != nullptr && use_direct_; }
  /// The KSP (for la/ only: NonlinearSolver applies its preconditioner).
  PetscKspHandle handle() const { return ksp_; }

 private:
  PetscKspHandle ksp_ = nullptr;
  /// y ← A x for the true residual (the operator of set_operator(s), kept alive by the caller).
  std::function<void(const Vector&, Vector&)> mult_;
  int baseline_iterations_ = -1;  ///< iterations of the first solve after the last build (reuse)
  bool rebuild_next_ = false;
  double rtol_ = 1e-8;
  PetscMatHandle op_ = nullptr;  ///< the assembled operator (set_operator), for the fallback
  bool fallback_allowed_ = false;
  PetscKspHandle direct_ = nullptr;  ///< the direct fallback's KSP, made on first use
  bool use_direct_ = false;          ///< the fallback was needed: every later solve is direct
  /// Solves by the direct fallback into report (reason, iterations, null pivots).
  void solve_direct(const Vector& b, Vector& x, SolveReport& report);
};

}  // namespace perimorph::la
