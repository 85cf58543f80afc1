#include "perimorph/la/nonlinear_solver.hpp"

#include "perimorph/la/petsc_check.hpp"

#include <petscsnes.h>

#include <exception>
#include <limits>
#include <utility>

namespace perimorph::la {

namespace {

// An exception does not cross PETSc's C frames: it is kept and rethrown
// after SNESSolve returns (NonlinearSolver::solve).
PetscErrorCode residual_callback(SNES /*snes*/, Vec u, Vec r, void* ctx) {
  auto& solver = *static_cast<NonlinearSolver*>(ctx);
  try {
    solver.evaluate_residual(u, r);
  } catch (...) {
    solver.callback_error = std::current_exception();
    return PETSC_ERR_LIB;
  }
  return 0;
}

PetscErrorCode jacobian_callback(SNES /*snes*/, Vec u, Mat /*J*/, Mat /*P*/, void* ctx) {
  auto& solver = *static_cast<NonlinearSolver*>(ctx);
  try {
    solver.evaluate_jacobian(u);
  } catch (...) {
    solver.callback_error = std::current_exception();
    return PETSC_ERR_LIB;
  }
  return 0;
}

/// PCSHELL apply: the preconditioner of another KSP (its context), set up for
/// that KSP's operator as PCSetUp decides (kept when it reuses it).
PetscErrorCode borrowed_preconditioner(PC pc, Vec x, Vec y) {
  void* ctx = nullptr;
  PetscCall(PCShellGetContext(pc, &ctx));
  PC inner = nullptr;
  PetscCall(KSPGetPC(static_cast<KSP>(ctx), &inner));
  PetscCall(PCApply(inner, x, y));
  return 0;
}

/// SNES's default test, and a stop when ||F|| fell by less than 10 % in each of
/// the last two steps: a kink of F (e.g. a cap) stalls Newton, and its steps
/// are then wasted work.
PetscErrorCode converged_or_stagnated(SNES snes, PetscInt it, PetscReal xnorm, PetscReal gnorm,
                                      PetscReal fnorm, SNESConvergedReason* reason, void* ctx) {
  PetscCall(SNESConvergedDefault(snes, it, xnorm, gnorm, fnorm, reason, nullptr));
  auto& solver = *static_cast<NonlinearSolver*>(ctx);
  auto& h = solver.residual_norms;
  if (it == 0) h.clear();
  h.push_back(fnorm);
  const std::size_t n = h.size();
  if (*reason == SNES_CONVERGED_ITERATING && n >= 3 && h[n - 1] > 0.9 * h[n - 2] &&
      h[n - 2] > 0.9 * h[n - 3]) {
    *reason = SNES_DIVERGED_DTOL;
    solver.stagnated = true;
  }
  return 0;
}

}  // namespace

NonlinearSolver::NonlinearSolver(Matrix& J, Residual residual, Jacobian jacobian, double rtol, double atol,
                                 int max_iterations, const std::string& options_prefix,
                                 const LinearSolver* preconditioner)
    : J_(J),
      residual_(std::move(residual)),
      jacobian_(std::move(jacobian)),
      r_(J.make_vector()),
      u_whole_(J.make_vector()),
      r_whole_(J.make_vector()) {
  PetscInt bs = 1;
  PM_PETSC(MatGetBlockSize(J_.handle(), &bs));
  // The assembly numbering's dofs: on a piece of the model, the piece's
  // (Distribution::num_nodes), not the matrix's global rows.
  const auto& distribution = J_.distribution();
  owned_ = OwnedDofs(distribution.get(), static_cast<int>(bs),
                     distribution ? distribution->num_nodes() * static_cast<Index>(bs) : J_.rows());
  PM_PETSC(SNESCreate(PETSC_COMM_WORLD, &snes_));
  PM_PETSC(SNESSetOptionsPrefix(snes_, options_prefix.c_str()));
  PM_PETSC(SNESSetType(snes_, SNESNEWTONLS));
  PM_PETSC(SNESSetFunction(snes_, r_.handle(), residual_callback, this));
  PM_PETSC(SNESSetJacobian(snes_, J_.handle(), J_.handle(), jacobian_callback, this));
  PM_PETSC(SNESSetTolerances(snes_, atol, rtol, PETSC_DEFAULT, max_iterations, PETSC_DEFAULT));
  KSP ksp = nullptr;
  PM_PETSC(SNESGetKSP(snes_, &ksp));
  PC pc = nullptr;
  PM_PETSC(KSPGetPC(ksp, &pc));
  if (preconditioner) {
    PM_PETSC(KSPSetType(ksp, KSPGMRES));
    // A step the borrowed preconditioner cannot solve in 200 iterations is
    // not worth solving: SNES stops (DIVERGED_LINEAR_SOLVE).
    PM_PETSC(KSPSetTolerances(ksp, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT, 200));
    PM_PETSC(PCSetType(pc, PCSHELL));
    PM_PETSC(PCShellSetContext(pc, preconditioner->handle()));
    PM_PETSC(PCShellSetApply(pc, borrowed_preconditioner));
    PM_PETSC(PCShellSetName(pc, "the run's preconditioner"));
  } else {
    PM_PETSC(KSPSetType(ksp, KSPPREONLY));
    PM_PETSC(PCSetType(pc, PCLU));
  }
  PM_PETSC(SNESSetConvergenceTest(snes_, converged_or_stagnated, this, nullptr));
  PM_PETSC(SNESSetFromOptions(snes_));
}

void NonlinearSolver::read_only(std::vector<Index> nodes, int block_size) {
  if (J_.distribution()) reads_.emplace(J_.distribution(), block_size, std::move(nodes));
}

std::vector<double> NonlinearSolver::gathered(PetscVecHandle u) {
  PM_PETSC(VecCopy(u, u_whole_.handle()));
  if (reads_) return reads_->gathered(u_whole_, std::numeric_limits<double>::quiet_NaN());
  return u_whole_.to_replicated();
}

void NonlinearSolver::evaluate_residual(PetscVecHandle u, PetscVecHandle r) {
  ++residual_evaluations;
  if (J_.distribution()) {
    const std::vector<double> x = gathered(u);
    std::vector<double> f(owned_.size());
    residual_(x, f);
    r_whole_.assign_owned(owned_, f);
    PM_PETSC(VecCopy(r_whole_.handle(), r));
    return;
  }
  PetscInt n = 0;
  PM_PETSC(VecGetLocalSize(u, &n));
  const PetscScalar* ua = nullptr;
  PetscScalar* ra = nullptr;
  PM_PETSC(VecGetArrayRead(u, &ua));
  PM_PETSC(VecGetArray(r, &ra));
  const auto size = static_cast<std::size_t>(n);
  residual_(std::span<const double>(ua, size), std::span<double>(ra, size));
  PM_PETSC(VecRestoreArray(r, &ra));
  PM_PETSC(VecRestoreArrayRead(u, &ua));
}

void NonlinearSolver::evaluate_jacobian(PetscVecHandle u) {
  J_.zero_entries();
  if (J_.distribution()) {
    jacobian_(gathered(u), J_);
  } else {
    PetscInt n = 0;
    PM_PETSC(VecGetLocalSize(u, &n));
    const PetscScalar* ua = nullptr;
    PM_PETSC(VecGetArrayRead(u, &ua));
    jacobian_(std::span<const double>(ua, static_cast<std::size_t>(n)), J_);
    PM_PETSC(VecRestoreArrayRead(u, &ua));
  }
  J_.finalize();
}

NonlinearSolver::~NonlinearSolver() {
  if (snes_) SNESDestroy(&snes_);
}

NonlinearReport NonlinearSolver::solve(Vector& u) {
  residual_evaluations = 0;
  stagnated = false;
  callback_error = nullptr;
  const PetscErrorCode status = SNESSolve(snes_, nullptr, u.handle());
  if (callback_error) std::rethrow_exception(std::exchange(callback_error, nullptr));
  PM_PETSC(status);
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
  report.reason = stagnated ? "STAGNATED (||F|| fell by less than 10 % in two consecutive steps)"
                            : SNESConvergedReasons[reason];
  PetscReal norm = 0.0;
  PM_PETSC(SNESGetFunctionNorm(snes_, &norm));
  report.residual_norm = norm;
  return report;
}

}  // namespace perimorph::la
