#include "perimorph/la/linear_solver.hpp"

#include "perimorph/la/petsc_check.hpp"
#include "perimorph/la/petsc_session.hpp"

#include <petscksp.h>

#include <algorithm>
#include <cstring>
#include <optional>

namespace perimorph::la {

LinearSolver::LinearSolver(double rtol, int max_iterations) : rtol_(rtol) {
  PM_PETSC(KSPCreate(PETSC_COMM_WORLD, &ksp_));
  PM_PETSC(KSPSetType(ksp_, KSPCG));
  PC pc = nullptr;
  PM_PETSC(KSPGetPC(ksp_, &pc));
  PM_PETSC(PCSetType(pc, PCGAMG));
  PM_PETSC(KSPSetTolerances(ksp_, rtol, PETSC_DEFAULT, PETSC_DEFAULT, max_iterations));
  PM_PETSC(KSPSetFromOptions(ksp_));
  // On more than one process a factorization must be a distributed one:
  // PETSc's own and CHOLMOD's are sequential, so SuperLU_DIST takes over from
  // them (the report's pc_type names it): its static schedule gives the same
  // bits run after run, where MUMPS' dynamic one does not (the flagship on 2
  // processes: every two MUMPS runs part at round-off from increment 18;
  // docs/benchmarks/distributed-runs.md). MUMPS when the options name it.
  PCType type = nullptr;
  PM_PETSC(PCGetType(pc, &type));
  if (world_size() > 1 && type != nullptr &&
      (std::strcmp(type, PCCHOLESKY) == 0 || std::strcmp(type, PCLU) == 0)) {
    MatSolverType solver = nullptr;
    PM_PETSC(PCFactorGetMatSolverType(pc, &solver));
    if (solver == nullptr ||
        (std::strcmp(solver, MATSOLVERMUMPS) != 0 && std::strcmp(solver, MATSOLVERSUPERLU_DIST) != 0))
      PM_PETSC(PCFactorSetMatSolverType(pc, MATSOLVERSUPERLU_DIST));
    // MUMPS' workspace estimate after its parallel analysis can fall short
    // (INFO(1) = −9: on 3 processes for the hole plate's first factor, with
    // the default 20 % margin); 50 % unless the options say otherwise.
    PM_PETSC(PCFactorGetMatSolverType(pc, &solver));
    PetscBool set = PETSC_FALSE;
    PM_PETSC(PetscOptionsHasName(nullptr, nullptr, "-mat_mumps_icntl_14", &set));
    if (solver != nullptr && std::strcmp(solver, MATSOLVERMUMPS) == 0 && !set)
      PM_PETSC(PetscOptionsSetValue(nullptr, "-mat_mumps_icntl_14", "50"));
  }
  // Warm start, except for a direct solve (preonly), which PETSc forbids it for.
  PetscBool preonly = PETSC_FALSE;
  PM_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(ksp_), KSPPREONLY, &preonly));
  PM_PETSC(KSPSetInitialGuessNonzero(ksp_, preonly ? PETSC_FALSE : PETSC_TRUE));
}

LinearSolver::~LinearSolver() {
  if (ksp_) KSPDestroy(&ksp_);
  if (direct_) KSPDestroy(&direct_);
}

void LinearSolver::solve_direct(const Vector& b, Vector& x, SolveReport& report) {
  if (!direct_) {
    PM_PETSC(KSPCreate(PETSC_COMM_WORLD, &direct_));
    PM_PETSC(KSPSetOptionsPrefix(direct_, "fallback_"));
    PM_PETSC(KSPSetType(direct_, KSPPREONLY));
    PC pc = nullptr;
    PM_PETSC(KSPGetPC(direct_, &pc));
    // LU: MUMPS detects null pivots in its unsymmetric factorization (with
    // the SPD flag set, PETSc's Cholesky asks MUMPS for an SPD one, which
    // does not).
    PM_PETSC(PCSetType(pc, PCLU));
    PM_PETSC(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
    PM_PETSC(KSPSetOperators(direct_, op_, op_));
    PM_PETSC(KSPSetFromOptions(direct_));
    PM_PETSC(PCFactorSetUpMatSolverType(pc));
    Mat F = nullptr;
    PM_PETSC(PCFactorGetMatrix(pc, &F));
    PM_PETSC(MatMumpsSetIcntl(F, 24, 1));    // null pivot detection
    PM_PETSC(MatMumpsSetCntl(F, 3, 1e-10));  // relative to the matrix norm
  }
  PM_PETSC(KSPSolve(direct_, b.read_handle(), x.handle()));
  KSPConvergedReason reason;
  PM_PETSC(KSPGetConvergedReason(direct_, &reason));
  report.reason = KSPConvergedReasons[reason];
  report.iterations = 0;
  report.direct_fallback = true;
  PC pc = nullptr;
  PM_PETSC(KSPGetPC(direct_, &pc));
  Mat F = nullptr;
  PM_PETSC(PCFactorGetMatrix(pc, &F));
  PetscInt nulls = 0;
  PM_PETSC(MatMumpsGetInfog(F, 28, &nulls));
  report.null_pivots = static_cast<int>(nulls);
  report.ksp_type = "preonly";
  report.pc_type = "lu (MUMPS, null pivots held)";
}

namespace {

/// Rigid-body modes from the dof-node coordinates (block size = dim), as the
/// near-null space of M (GAMG's coarse spaces); distributed (`d` not null),
/// those of the nodes this process owns, in the distributed order.
void attach_rigid_body_modes(PetscMatHandle M, Index rows, const NodeCoordinate& node_coordinate, int dim,
                             const Distribution* d) {
  const Index nodes = d != nullptr ? d->num_nodes() : rows / dim;
  const auto owned = static_cast<std::size_t>(d != nullptr ? d->owned_nodes() : nodes);
  Vec coords = nullptr;
  PM_PETSC(VecCreate(PETSC_COMM_WORLD, &coords));
  PM_PETSC(VecSetSizes(coords, static_cast<PetscInt>(owned) * dim, PETSC_DECIDE));
  PM_PETSC(VecSetBlockSize(coords, dim));
  PM_PETSC(VecSetType(coords, VECSTANDARD));
  PetscScalar* c = nullptr;
  PM_PETSC(VecGetArray(coords, &c));
  for (Index n = 0; n < nodes; ++n) {
    auto at = static_cast<std::size_t>(n);
    if (d != nullptr) {
      if (!d->owns(n)) continue;
      at = static_cast<std::size_t>(d->to_distributed[static_cast<std::size_t>(n)] - d->begin);
    }
    const Vec3 x = node_coordinate(n);
    for (int k = 0; k < dim; ++k) c[at * static_cast<std::size_t>(dim) + static_cast<std::size_t>(k)] = x[k];
  }
  PM_PETSC(VecRestoreArray(coords, &c));
  MatNullSpace nullsp = nullptr;
  PM_PETSC(MatNullSpaceCreateRigidBody(coords, &nullsp));
  PM_PETSC(MatSetNearNullSpace(M, nullsp));
  PM_PETSC(MatNullSpaceDestroy(&nullsp));
  PM_PETSC(VecDestroy(&coords));
}

}  // namespace

void LinearSolver::set_operator(Matrix& A, const NodeCoordinate& node_coordinate, int dim) {
  mult_ = [&A](const Vector& x, Vector& y) { A.mult(x, y); };
  op_ = A.handle();
  if (direct_) PM_PETSC(KSPSetOperators(direct_, op_, op_));
  attach_rigid_body_modes(A.handle(), A.rows(), node_coordinate, dim, A.distribution().get());
  PM_PETSC(KSPSetOperators(ksp_, A.handle(), A.handle()));
}

void LinearSolver::set_operators(const ShellMatrix& A, Matrix& P, const NodeCoordinate& node_coordinate,
                                 int dim) {
  mult_ = [&A](const Vector& x, Vector& y) { A.mult(x, y); };
  op_ = nullptr;  // no entries: no direct fallback
  attach_rigid_body_modes(P.handle(), P.rows(), node_coordinate, dim, P.distribution().get());
  PM_PETSC(KSPSetOperators(ksp_, A.handle(), P.handle()));
}

SolveReport LinearSolver::solve(const Vector& b, Vector& x) {
  PERIMORPH_ASSERT(static_cast<bool>(mult_), "set_operator must be called before solve");
  auto true_residual = [&](SolveReport& rep) {
    Vector r(b.size(), 1);
    mult_(x, r);
    r.axpy(-1.0, b);
    const double bnorm = b.norm2();
    rep.relative_residual = bnorm > 0 ? r.norm2() / bnorm : r.norm2();
  };
  const double fallback_tolerance = std::max(10.0 * rtol_, 1e-9);
  if (use_direct_ && op_) {
    SolveReport report;
    solve_direct(b, x, report);
    true_residual(report);
    if (report.relative_residual > fallback_tolerance || !x.all_finite())
      throw SolverError(fmt::format(
          "the direct solve (MUMPS, {} null pivots held) left a relative residual {:.3e}: the loads do work "
          "on a mechanism that bond failures have left, and there is no quasi-static equilibrium",
          report.null_pivots, report.relative_residual));
    return report;
  }
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
    // A direct solve (preonly) has no iterations to make up for a factor of
    // an earlier operator: it is accepted only if it solves this one to rtol.
    PetscBool preonly = PETSC_FALSE;
    PM_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(ksp_), KSPPREONLY, &preonly));
    if (preonly && first >= 0) {
      SolveReport probe;
      true_residual(probe);
      if (!(probe.relative_residual <= rtol_)) first = KSP_DIVERGED_PC_FAILED;
    }
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

  true_residual(report);

  if (reason < 0 && fallback_allowed_ && op_) {
    const std::string krylov = fmt::format("{} + {}: {} after {} iterations", report.ksp_type, report.pc_type,
                                           report.reason, report.iterations);
    if (x0) x.copy_from(*x0);
    SolveReport direct;
    solve_direct(b, x, direct);
    true_residual(direct);
    direct.rebuilt_preconditioner = rebuilt;
    if (direct.relative_residual <= fallback_tolerance && x.all_finite()) {
      use_direct_ = true;
      return direct;
    }
    throw SolverError(fmt::format(
        "the linear solver ({}) diverged, and the direct solve that holds null pivots (MUMPS, {} found) left "
        "a "
        "relative residual {:.3e}: the loads do work on a mechanism, there is no quasi-static equilibrium",
        krylov, direct.null_pivots, direct.relative_residual));
  }
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
