// la::LinearSolver with -ksp_reuse_preconditioner: a preconditioner built for
// an earlier matrix that makes the Krylov solve fail on the present one is
// rebuilt and the solve retried (reported); one under which the iterations
// grew beyond 2 n + 10 is rebuilt before the next solve; without reuse
// nothing is retried; a solve that fails also with the rebuilt
// preconditioner throws and says so; a direct solve (preonly) with a factor
// of an earlier matrix is redone with a new one. The direct fallback (allowed after bond
// failures) solves a singular, consistent system by holding its null pivot,
// and every later solve is direct; with an inconsistent right-hand side (a
// load that does work on the mechanism) it throws; not allowed, it is not used.

#include "perimorph/la/linear_solver.hpp"
#include "perimorph/assembly/sparsity.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/la/petsc_session.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <string>
#include <vector>

namespace perimorph {
namespace {

constexpr int n = 4;
/// Every node at the origin (the rigid-body modes of these scalar tests).
const la::NodeCoordinate at_origin = [](Index) -> Vec3 { return Vec3::Zero(); };

assembly::SparsityPattern diagonal_pattern() {
  assembly::SparsityPattern p;
  p.block_size = 1;
  p.row_offsets = {0, 1, 2, 3, 4};
  p.columns = {0, 1, 2, 3};
  return p;
}

void set_diagonal(la::Matrix& A, const std::array<double, n>& d) {
  A.zero_entries();
  for (Index i = 0; i < n; ++i) {
    const std::array<Index, 1> row{i};
    const std::array<double, 1> v{d[static_cast<std::size_t>(i)]};
    A.add(row, row, v);
  }
  A.finalize();
}

/// Jacobi is exact on a diagonal matrix: one CG iteration when it is built for
/// the matrix; the identity (Jacobi of I, reused) needs four on diag(1, 10, 100, 1000).
struct LaLinearSolverReuse : ::testing::Test {
  // Set explicitly: the options database is global and other tests of the
  // same process may have left a solver in it.
  void SetUp() override {
    la::set_option("-ksp_type", "cg");
    la::set_option("-pc_type", "jacobi");
    la::set_option("-ksp_rtol", "1e-10");
    la::set_option("-ksp_max_it", "1");
  }
  void TearDown() override {
    for (const char* o : {"-ksp_type", "-pc_type", "-ksp_rtol", "-ksp_max_it", "-ksp_reuse_preconditioner"})
      la::clear_option(o);
  }
  la::NodeCoordinate nodes = at_origin;
};

TEST_F(LaLinearSolverReuse, ReusedPreconditionerThatFailsIsRebuiltAndTheSolveRetried) {
  la::set_option("-ksp_reuse_preconditioner");
  la::LinearSolver solver(1e-10, 1);
  la::Matrix A(diagonal_pattern());
  la::Vector b(n, 1), x(n, 1);
  b.set_all(1.0);
  set_diagonal(A, {1, 1, 1, 1});
  solver.set_operator(A, nodes, 1);
  x.set_all(0.0);
  EXPECT_FALSE(solver.solve(b, x).rebuilt_preconditioner);

  set_diagonal(A, {1, 10, 100, 1000});
  solver.set_operator(A, nodes, 1);
  x.set_all(0.0);
  const la::SolveReport rep = solver.solve(b, x);
  EXPECT_TRUE(rep.rebuilt_preconditioner);
  EXPECT_LT(rep.relative_residual, 1e-12);
  const std::vector<double> xs = x.to_std();
  EXPECT_NEAR(xs[3], 1e-3, 1e-15);

  // The rebuilt preconditioner is reused again: the same matrix needs no rebuild.
  x.set_all(0.0);
  EXPECT_FALSE(solver.solve(b, x).rebuilt_preconditioner);
}

TEST(LaLinearSolverReuseFactor, AKeptCholeskyFactorSolvesARankOneChangeInTwoIterations) {
  // A failed bond removes a rank-one block: with the factor of the matrix
  // before it, the preconditioned operator is I − (rank one), so CG converges
  // in at most two iterations (exact arithmetic) and the factor is kept. The
  // solver the fracture examples use (CG + a kept MUMPS Cholesky factor).
  constexpr int m = 30;
  la::set_option("-ksp_type", "cg");
  la::set_option("-pc_type", "cholesky");
  la::set_option("-pc_factor_mat_solver_type", "mumps");
  la::set_option("-ksp_reuse_preconditioner");
  la::LinearSolver solver(1e-12, 1000);
  for (const char* o : {"-ksp_type", "-pc_type", "-pc_factor_mat_solver_type", "-ksp_reuse_preconditioner"})
    la::clear_option(o);
  // A chain of m springs of stiffness 1 + i, held at one end: K is SPD and tridiagonal.
  assembly::SparsityPattern p;
  p.block_size = 1;
  p.row_offsets.push_back(0);
  for (int i = 0; i < m; ++i) {
    for (int j = std::max(0, i - 1); j <= std::min(m - 1, i + 1); ++j) p.columns.push_back(j);
    p.row_offsets.push_back(static_cast<Index>(p.columns.size()));
  }
  la::Matrix A(p);
  auto add_spring = [&](int i, double k) {  // between dof i − 1 (or the support) and dof i
    if (i == 0) {
      const std::array<Index, 1> r{0};
      const std::array<double, 1> v{k};
      A.add(r, r, v);
      return;
    }
    const std::array<Index, 2> r{i - 1, i};
    const std::array<double, 4> v{k, -k, -k, k};
    A.add(r, r, v);
  };
  A.zero_entries();
  for (int i = 0; i < m; ++i) add_spring(i, 1.0 + i);
  A.finalize();
  const la::NodeCoordinate points = at_origin;
  la::Vector b(m, 1), x(m, 1);
  b.set_all(1.0);
  solver.set_operator(A, points, 1);
  x.set_all(0.0);
  EXPECT_LE(solver.solve(b, x).iterations, 1);  // the factor of this matrix: exact
  add_spring(17, -0.5 * (1.0 + 17));            // the spring of dof 17 loses half its stiffness: rank one
  A.finalize();
  solver.set_operator(A, points, 1);
  const la::SolveReport changed = solver.solve(b, x);
  EXPECT_FALSE(changed.rebuilt_preconditioner);
  EXPECT_LE(changed.iterations, 2);
  EXPECT_LE(changed.relative_residual, 1e-10);
}

TEST_F(LaLinearSolverReuse, ADirectSolveWithAnOldFactorIsRedoneWithANewOne) {
  // preonly has no iterations to make up for a factor of an earlier matrix:
  // kept, it would return that matrix's solution (relative residual 0.9 here).
  la::set_option("-ksp_type", "preonly");
  la::set_option("-pc_type", "lu");
  la::set_option("-ksp_reuse_preconditioner");
  la::LinearSolver solver(1e-10, 1);
  la::Matrix A(diagonal_pattern());
  la::Vector b(n, 1), x(n, 1);
  b.set_all(1.0);
  set_diagonal(A, {1, 1, 1, 1});
  solver.set_operator(A, nodes, 1);
  EXPECT_FALSE(solver.solve(b, x).rebuilt_preconditioner);
  set_diagonal(A, {1, 10, 100, 1000});
  solver.set_operator(A, nodes, 1);
  const la::SolveReport rep = solver.solve(b, x);
  EXPECT_TRUE(rep.rebuilt_preconditioner);
  EXPECT_LT(rep.relative_residual, 1e-14);
  EXPECT_NEAR(x.to_std()[3], 1e-3, 1e-18);
  // The same matrix again: the new factor is kept.
  EXPECT_FALSE(solver.solve(b, x).rebuilt_preconditioner);
}

TEST(LaLinearSolverReuseGrowth,
     IterationsGrownBeyondTwiceTheirCountAfterTheBuildRebuildItBeforeTheNextSolve) {
  // 40 distinct eigenvalues: CG with the identity (Jacobi of I, reused) needs
  // up to 40 iterations, with Jacobi of the matrix one.
  constexpr int m = 40;
  la::set_option("-ksp_type", "cg");
  la::set_option("-pc_type", "jacobi");
  la::set_option("-ksp_reuse_preconditioner");
  la::LinearSolver solver(1e-10, 1000);
  for (const char* o : {"-ksp_type", "-pc_type", "-ksp_reuse_preconditioner"}) la::clear_option(o);
  assembly::SparsityPattern p;
  p.block_size = 1;
  for (int i = 0; i <= m; ++i) p.row_offsets.push_back(i);
  for (int i = 0; i < m; ++i) p.columns.push_back(i);
  la::Matrix A(p);
  auto set = [&](bool identity) {
    A.zero_entries();
    for (Index i = 0; i < m; ++i) {
      const std::array<Index, 1> row{i};
      const std::array<double, 1> v{identity ? 1.0 : 1.0 + 10.0 * static_cast<double>(i)};
      A.add(row, row, v);
    }
    A.finalize();
  };
  const la::NodeCoordinate points = at_origin;
  la::Vector b(m, 1), x(m, 1);
  b.set_all(1.0);
  set(true);
  solver.set_operator(A, points, 1);
  x.set_all(0.0);
  EXPECT_LE(solver.solve(b, x).iterations, 1);  // the first build: the baseline
  set(false);
  solver.set_operator(A, points, 1);
  x.set_all(0.0);
  const la::SolveReport grown = solver.solve(b, x);  // converges, with the stale preconditioner
  EXPECT_FALSE(grown.rebuilt_preconditioner);
  EXPECT_GT(grown.iterations, 12);
  x.set_all(0.0);
  const la::SolveReport next = solver.solve(b, x);
  EXPECT_TRUE(next.rebuilt_preconditioner);
  EXPECT_LE(next.iterations, 1);
  x.set_all(0.0);
  EXPECT_FALSE(solver.solve(b, x).rebuilt_preconditioner);  // the new baseline holds
}

TEST_F(LaLinearSolverReuse, WithoutReuseNothingIsRetried) {
  la::LinearSolver solver(1e-10, 1);
  la::Matrix A(diagonal_pattern());
  la::Vector b(n, 1), x(n, 1);
  b.set_all(1.0);
  set_diagonal(A, {1, 1, 1, 1});
  solver.set_operator(A, nodes, 1);
  x.set_all(0.0);
  solver.solve(b, x);
  set_diagonal(A, {1, 10, 100, 1000});
  solver.set_operator(A, nodes, 1);
  x.set_all(0.0);
  EXPECT_FALSE(solver.solve(b, x).rebuilt_preconditioner);
}

TEST_F(LaLinearSolverReuse, FailureWithTheRebuiltPreconditionerThrowsAndSaysSo) {
  la::set_option("-ksp_reuse_preconditioner");
  la::set_option("-pc_type", "none");
  la::LinearSolver solver(1e-10, 1);
  la::Matrix A(diagonal_pattern());
  la::Vector b(n, 1), x(n, 1);
  b.set_all(1.0);
  set_diagonal(A, {1, 10, 100, 1000});
  solver.set_operator(A, nodes, 1);
  x.set_all(0.0);
  try {
    solver.solve(b, x);
    FAIL() << "expected a SolverError";
  } catch (const SolverError& e) {
    EXPECT_NE(std::string(e.what()).find("rebuilt"), std::string::npos) << e.what();
  }
}

/// [[2, −1], [−1, 2]] ⊕ [[1, −1], [−1, 1]]: the second block is singular,
/// (1, 1) its null vector (a mechanism).
la::Matrix singular_matrix() {
  assembly::SparsityPattern p;
  p.block_size = 1;
  p.row_offsets = {0, 2, 4, 6, 8};
  p.columns = {0, 1, 0, 1, 2, 3, 2, 3};
  la::Matrix A(p);
  const std::array<Index, 2> first{0, 1}, second{2, 3};
  const std::array<double, 4> spd{2, -1, -1, 2}, mechanism{1, -1, -1, 1};
  A.add(first, first, spd);
  A.add(second, second, mechanism);
  A.finalize();
  A.set_spd();
  return A;
}

TEST_F(LaLinearSolverReuse, DirectFallbackHoldsTheNullPivotOfAConsistentSystem) {
  // CG with one iteration fails (DIVERGED_ITS); the direct solve holds the null pivot.
  la::LinearSolver solver(1e-10, 1);
  la::Matrix A = singular_matrix();
  solver.set_operator(A, nodes, 1);
  la::Vector b(n, 1), x(n, 1);
  b.assign(std::vector<double>{1.0, 0.0, 1.0, -1.0});  // balanced on the mechanism
  EXPECT_THROW(solver.solve(b, x), SolverError);       // not allowed
  solver.allow_direct_fallback(true);
  x.set_all(0.0);
  const la::SolveReport rep = solver.solve(b, x);
  EXPECT_TRUE(rep.direct_fallback);
  EXPECT_EQ(rep.null_pivots, 1);
  EXPECT_LT(rep.relative_residual, 1e-12);
  EXPECT_TRUE(solver.direct());
  const std::vector<double> u = x.to_std();
  EXPECT_NEAR(u[0], 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(u[1], 1.0 / 3.0, 1e-12);
  EXPECT_NEAR(u[2] - u[3], 1.0, 1e-12);  // the mechanism's stretch; its rigid motion held
  // Every later solve is direct.
  x.set_all(0.0);
  EXPECT_TRUE(solver.solve(b, x).direct_fallback);
}

TEST_F(LaLinearSolverReuse, DirectFallbackRefusesALoadThatDoesWorkOnTheMechanism) {
  la::LinearSolver solver(1e-10, 1);
  la::Matrix A = singular_matrix();
  solver.set_operator(A, nodes, 1);
  solver.allow_direct_fallback(true);
  la::Vector b(n, 1), x(n, 1);
  b.assign(std::vector<double>{1.0, 0.0, 1.0, 1.0});  // (1, 1) · (1, 1) ≠ 0
  try {
    solver.solve(b, x);
    FAIL() << "expected a SolverError";
  } catch (const SolverError& e) {
    std::printf("%s\n", e.what());
    EXPECT_NE(std::string(e.what()).find("no quasi-static equilibrium"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace perimorph
