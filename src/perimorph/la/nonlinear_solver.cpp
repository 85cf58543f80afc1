#include "perimorph/la/nonlinear_solver.hpp"

#include "perimorph/la/petsc_check.hpp"

#include <petscsnes.h>

namespace perimorph::la {

namespace {

PetscErrorCode residual_callback(SNES /*snes*/, Vec u, Vec r, void* ctx) {
  auto& solver = *static_cast<NonlinearSolver*>(ctx);
  PetscInt n = 0;
  PetscCall(VecGetLocalSize(u, &n));
  const PetscScalar* ua = nullptr;
  PetscScalar* ra = nullptr;
  PetscCall(VecGetArrayRead(u, &ua));
  PetscCall(VecGetArray(r, &ra));
  const auto size = static_cast<std::size_t>(n);
  solver.residual()(std::span<const double>(ua, size), std::span<double>(ra, size));
  PetscCall(VecRestoreArray(r, &ra));
  PetscCall(VecRestoreArrayRead(u, &ua));
  ++solver.residual_evaluations;
  return 0;
}

PetscErrorCode jacobian_callback(SNES /*snes*/, Vec u, Mat /*J*/, Mat /*P*/, void* ctx) {
  auto& solver = *static_cast<NonlinearSolver*>(ctx);
  PetscInt n = 0;
  PetscCall(VecGetLocalSize(u, &n));
  const PetscScalar* ua = nullptr;
  PetscCall(VecGetArrayRead(u, &ua));
  Matrix& J = solver.jacobian_matrix();
  J.zero_entries();
  solver.jacobian()(std::span<const double>(ua, static_cast<std::size_t>(n)), J);
  J.finalize();
  PetscCall(VecRestoreArrayRead(u, &ua));
  return 0;
}

}  // namespace

NonlinearSolver::NonlinearSolver(Matrix& J, Residual residual, Jacobian jacobian, double rtol, double atol,
                                 int max_iterations, const std::string& options_prefix)
    : J_(J), residual_(std::move(residual)), jacobian_(std::move(jacobian)), r_(J.rows(), 1) {
  PM_PETSC(SNESCreate(PETSC_COMM_WORLD, &snes_));
  PM_PETSC(SNESSetOptionsPrefix(snes_, options_prefix.c_str()));
  PM_PETSC(SNESSetType(snes_, SNESNEWTONLS));
  PM_PETSC(SNESSetFunction(snes_, r_.handle(), residual_callback, this));
  PM_PETSC(SNESSetJacobian(snes_, J_.handle(), J_.handle(), jacobian_callback, this));
  PM_PETSC(SNESSetTolerances(snes_, atol, rtol, PETSC_DEFAULT, max_iterations, PETSC_DEFAULT));
  KSP ksp = nullptr;
  PM_PETSC(SNESGetKSP(snes_, &ksp));
  PM_PETSC(KSPSetType(ksp, KSPPREONLY));
  PC pc = nullptr;
  PM_PETSC(KSPGetPC(ksp, &pc));
  PM_PETSC(PCSetType(pc, PCLU));
  PM_PETSC(SNESSetFromOptions(snes_));
}

NonlinearSolver::~NonlinearSolver() {
  if (snes_) SNESDestroy(&snes_);
}

NonlinearReport NonlinearSolver::solve(Vector& u) {
  residual_evaluations = 0;
  PM_PETSC(SNESSolve(snes_, nullptr, u.handle()));
  NonlinearReport report;
  SNESConvergedReason reason;
  PM_PETSC(SNESGetConvergedReason(snes_, &reason));
  PetscInt its = 0, lits = 0;
  PM_PETSC(SNESGetIterationNumber(snes_, &its));
  PM_PETSC(SNESGetLinearSolveIterations(snes_, &lits));
  KSP ksp = nullptr;
  PM_PETSC(SNESGetKSP(snes_, &ksp));
  PetscBool preonly = PETSC_FALSE;
  PM_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(ksp), KSPPREONLY, &preonly));
  report.iterations = static_cast<int>(its);
  // preonly reports no Krylov iterations: one solve per Newton step.
  report.linear_solves = preonly ? static_cast<int>(its) : static_cast<int>(lits);
  report.residual_evaluations = residual_evaluations;
  report.converged = reason > 0;
  report.reason = SNESConvergedReasons[reason];
  PetscReal norm = 0.0;
  PM_PETSC(SNESGetFunctionNorm(snes_, &norm));
  report.residual_norm = norm;
  return report;
}

}  // namespace perimorph::la
