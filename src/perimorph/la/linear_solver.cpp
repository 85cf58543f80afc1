#include "perimorph/la/linear_solver.hpp"

#include "perimorph/la/petsc_check.hpp"

#include <petscksp.h>

#include <optional>

namespace perimorph::la {

LinearSolver::LinearSolver(double rtol, int max_iterations) {
  PM_PETSC(KSPCreate(PETSC_COMM_WORLD, &ksp_));
  PM_PETSC(KSPSetType(ksp_, KSPCG));
  PC pc = nullptr;
  PM_PETSC(KSPGetPC(ksp_, &pc));
  PM_PETSC(PCSetType(pc, PCGAMG));
  PM_PETSC(KSPSetTolerances(ksp_, rtol, PETSC_DEFAULT, PETSC_DEFAULT, max_iterations));
  PM_PETSC(KSPSetFromOptions(ksp_));
  // Warm start, except for a direct solve (preonly), which PETSc forbids it for.
  PetscBool preonly = PETSC_FALSE;
  PM_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(ksp_), KSPPREONLY, &preonly));
  PM_PETSC(KSPSetInitialGuessNonzero(ksp_, preonly ? PETSC_FALSE : PETSC_TRUE));
}

LinearSolver::~LinearSolver() {
  if (ksp_) KSPDestroy(&ksp_);
}

namespace {

/// Rigid-body modes from the dof-node coordinates (block size = dim), as the
/// near-null space of M (GAMG's coarse spaces).
void attach_rigid_body_modes(PetscMatHandle M, std::span<const Vec3> node_coordinates, int dim) {
  Vec coords = nullptr;
  PM_PETSC(VecCreate(PETSC_COMM_WORLD, &coords));
  PM_PETSC(VecSetSizes(coords, static_cast<PetscInt>(node_coordinates.size()) * dim, PETSC_DECIDE));
  PM_PETSC(VecSetBlockSize(coords, dim));
  PM_PETSC(VecSetType(coords, VECSTANDARD));
  PetscScalar* c = nullptr;
  PM_PETSC(VecGetArray(coords, &c));
  for (std::size_t n = 0; n < node_coordinates.size(); ++n)
    for (int d = 0; d < dim; ++d)
      c[n * static_cast<std::size_t>(dim) + static_cast<std::size_t>(d)] = node_coordinates[n][d];
  PM_PETSC(VecRestoreArray(coords, &c));
  MatNullSpace nullsp = nullptr;
  PM_PETSC(MatNullSpaceCreateRigidBody(coords, &nullsp));
  PM_PETSC(MatSetNearNullSpace(M, nullsp));
  PM_PETSC(MatNullSpaceDestroy(&nullsp));
  PM_PETSC(VecDestroy(&coords));
}

}  // namespace

void LinearSolver::set_operator(Matrix& A, std::span<const Vec3> node_coordinates, int dim) {
  mult_ = [&A](const Vector& x, Vector& y) { A.mult(x, y); };
  attach_rigid_body_modes(A.handle(), node_coordinates, dim);
  PM_PETSC(KSPSetOperators(ksp_, A.handle(), A.handle()));
}

void LinearSolver::set_operators(const ShellMatrix& A, Matrix& P, std::span<const Vec3> node_coordinates,
                                 int dim) {
  mult_ = [&A](const Vector& x, Vector& y) { A.mult(x, y); };
  attach_rigid_body_modes(P.handle(), node_coordinates, dim);
  PM_PETSC(KSPSetOperators(ksp_, A.handle(), P.handle()));
}

SolveReport LinearSolver::solve(const Vector& b, Vector& x) {
  PERIMORPH_ASSERT(static_cast<bool>(mult_), "set_operator must be called before solve");
  PetscBool reuse = PETSC_FALSE;
  PM_PETSC(KSPGetReusePreconditioner(ksp_, &reuse));
  // A reused preconditioner was built for an earlier operator (before bonds failed or alpha
  // grew). It is rebuilt for the present operator before this solve when the last solve needed
  // more than twice the iterations (+ 10) of the first one after the last build; and when the
  // Krylov solve diverges with it, it is rebuilt and the solve retried once from the same
  // initial guess, so that the reuse stays an optimisation and never decides whether a run
  // can go on.
  std::optional<Vector> x0;
  if (reuse) {
    x0.emplace(x.size(), 1);
    x0->copy_from(x);
  }
  const bool rebuild_now = reuse && rebuild_next_;
  if (rebuild_now) PM_PETSC(KSPSetReusePreconditioner(ksp_, PETSC_FALSE));
  PM_PETSC(KSPSolve(ksp_, b.read_handle(), x.handle()));
  if (rebuild_now) PM_PETSC(KSPSetReusePreconditioner(ksp_, PETSC_TRUE));
  bool rebuilt = rebuild_now;
  if (reuse && !rebuild_now) {
    KSPConvergedReason first;
    PM_PETSC(KSPGetConvergedReason(ksp_, &first));
    if (first < 0) {
      x.copy_from(*x0);
      PM_PETSC(KSPSetReusePreconditioner(ksp_, PETSC_FALSE));
      PM_PETSC(KSPSolve(ksp_, b.read_handle(), x.handle()));
      PM_PETSC(KSPSetReusePreconditioner(ksp_, PETSC_TRUE));
      rebuilt = true;
    }
  }
  SolveReport report;
  KSPConvergedReason reason;
  PM_PETSC(KSPGetConvergedReason(ksp_, &reason));
  PetscInt its = 0;
  PM_PETSC(KSPGetIterationNumber(ksp_, &its));
  report.iterations = static_cast<int>(its);
  if (reuse) {
    if (rebuilt || baseline_iterations_ < 0) {
      baseline_iterations_ = report.iterations;
      rebuild_next_ = false;
    } else if (report.iterations > 2 * baseline_iterations_ + 10) {
      rebuild_next_ = true;
    }
  }
  report.reason = KSPConvergedReasons[reason];
  report.rebuilt_preconditioner = rebuilt;
  KSPType ktype = nullptr;
  PM_PETSC(KSPGetType(ksp_, &ktype));
  PC pc = nullptr;
  PM_PETSC(KSPGetPC(ksp_, &pc));
  PCType ptype = nullptr;
  PM_PETSC(PCGetType(pc, &ptype));
  report.ksp_type = ktype ? ktype : "";
  report.pc_type = ptype ? ptype : "";

  Vector r(b.size(), 1);
  mult_(x, r);
  r.axpy(-1.0, b);
  const double bnorm = b.norm2();
  report.relative_residual = bnorm > 0 ? r.norm2() / bnorm : r.norm2();

  if (reason < 0)
    throw SolverError(fmt::format(
        "the linear solver ({} + {}) diverged: {} after {} iterations, relative residual {:.3e}{}. "
        "Try a direct solve (-ksp_type preonly -pc_type cholesky), more iterations (-ksp_max_it), "
        "or check the boundary conditions: an unconstrained rigid-body motion makes the matrix singular",
        report.ksp_type, report.pc_type, report.reason, report.iterations, report.relative_residual,
        rebuilt ? " (also with the reused preconditioner rebuilt for this matrix)" : ""));
  if (!x.all_finite() || !std::isfinite(report.relative_residual))
    throw SolverError(
        fmt::format("the solution contains NaN or Inf ({} + {}, {} iterations); the matrix is "
                    "probably singular or the material data invalid",
                    report.ksp_type, report.pc_type, report.iterations));
  return report;
}

}  // namespace perimorph::la
