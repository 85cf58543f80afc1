// la::NonlinearSolver (PETSc SNES): Newton on a small coupled system converges
// to the known root, quadratically (few steps, each one direct solve); the
// callbacks see the iterate and fill r and J; a root that does not exist is
// reported, not thrown.

#include "perimorph/la/nonlinear_solver.hpp"
#include "perimorph/assembly/sparsity.hpp"
#include "perimorph/la/petsc_session.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace perimorph {
namespace {

/// 3 unknowns coupled as a chain (tridiagonal pattern).
assembly::SparsityPattern chain3() {
  assembly::SparsityPattern p;
  p.block_size = 1;
  p.row_offsets = {0, 2, 5, 7};
  p.columns = {0, 1, 0, 1, 2, 1, 2};
  return p;
}

// F_i(u) = u_i³ + (2u_i − u_{i−1} − u_{i+1}) − b_i, b chosen so that u* = (1, 2, 3).
constexpr double root[3] = {1.0, 2.0, 3.0};

double chain(const double* u, int i) {
  return 2 * u[i] - (i > 0 ? u[i - 1] : 0.0) - (i < 2 ? u[i + 1] : 0.0);
}

TEST(LaNonlinearSolver, NewtonFindsTheRootOfACoupledCubicInFewSteps) {
  la::Matrix J(chain3());
  double b[3];
  for (int i = 0; i < 3; ++i) b[i] = std::pow(root[i], 3) + chain(root, i);
  int jacobians = 0;
  la::NonlinearSolver snes(
      J,
      [&](std::span<const double> u, std::span<double> r) {
        for (int i = 0; i < 3; ++i)
          r[static_cast<std::size_t>(i)] =
              std::pow(u[static_cast<std::size_t>(i)], 3) + chain(u.data(), i) - b[i];
      },
      [&](std::span<const double> u, la::Matrix& Jm) {
        ++jacobians;
        for (Index i = 0; i < 3; ++i) {
          const Index row[1] = {i};
          const double d[1] = {3 * u[static_cast<std::size_t>(i)] * u[static_cast<std::size_t>(i)] + 2.0};
          Jm.add(row, row, d);
          for (Index j : {i - 1, i + 1}) {
            if (j < 0 || j > 2) continue;
            const Index col[1] = {j};
            const double off[1] = {-1.0};
            Jm.add(row, col, off);
          }
        }
      },
      1e-12, 1e-14, 50, "test_newton_");
  la::Vector u(3, 1);
  u.set_all(1.5);
  const auto rep = snes.solve(u);
  EXPECT_TRUE(rep.converged) << rep.reason;
  const auto x = u.to_std();
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(x[static_cast<std::size_t>(i)], root[i], 1e-10);
  // Quadratic convergence from a start within 1.5 of the root: a handful of steps.
  EXPECT_LE(rep.iterations, 8);
  EXPECT_EQ(rep.linear_solves, rep.iterations) << "one direct solve per Newton step";
  EXPECT_EQ(jacobians, rep.iterations);
  EXPECT_LT(rep.residual_norm, 1e-10);
}

TEST(LaNonlinearSolver, StepsByGmresWithTheRunsPreconditionerFindTheSameRoot) {
  // The preconditioner of a linear solver on the chain part alone (what the
  // damage Newton borrows from the run's solver: that of A, not of J).
  la::set_option("-pc_type", "jacobi");
  la::set_option("-ksp_type", "cg");
  la::Matrix A(chain3());
  for (Index i = 0; i < 3; ++i)
    for (Index j : {i - 1, i, i + 1}) {
      if (j < 0 || j > 2) continue;
      const Index row[1] = {i}, col[1] = {j};
      const double v[1] = {i == j ? 2.0 : -1.0};
      A.add(row, col, v);
    }
  A.finalize();
  la::LinearSolver linear(1e-10, 100);
  const la::NodeCoordinate nodes = [](Index) -> Vec3 { return Vec3::Zero(); };
  linear.set_operator(A, nodes, 1);
  la::clear_option("-pc_type");
  la::clear_option("-ksp_type");
  la::Matrix J(chain3());
  double b[3];
  for (int i = 0; i < 3; ++i) b[i] = std::pow(root[i], 3) + chain(root, i);
  la::NonlinearSolver snes(
      J,
      [&](std::span<const double> u, std::span<double> r) {
        for (int i = 0; i < 3; ++i)
          r[static_cast<std::size_t>(i)] =
              std::pow(u[static_cast<std::size_t>(i)], 3) + chain(u.data(), i) - b[i];
      },
      [&](std::span<const double> u, la::Matrix& Jm) {
        for (Index i = 0; i < 3; ++i) {
          const Index row[1] = {i};
          const double d[1] = {3 * u[static_cast<std::size_t>(i)] * u[static_cast<std::size_t>(i)] + 2.0};
          Jm.add(row, row, d);
          for (Index j : {i - 1, i + 1}) {
            if (j < 0 || j > 2) continue;
            const Index col[1] = {j};
            const double off[1] = {-1.0};
            Jm.add(row, col, off);
          }
        }
      },
      1e-12, 1e-14, 50, "test_borrowed_", &linear);
  la::Vector u(3, 1);
  u.set_all(1.5);
  const auto rep = snes.solve(u);
  EXPECT_TRUE(rep.converged) << rep.reason;
  const auto x = u.to_std();
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(x[static_cast<std::size_t>(i)], root[i], 1e-10);
  EXPECT_LE(rep.iterations, 8);
  EXPECT_GE(rep.linear_solves, rep.iterations) << "Krylov iterations, at least one per step";
}

TEST(LaNonlinearSolver, AnEquationWithoutARootIsReportedNotThrown) {
  // F(u) = u² + 1 has no real root.
  assembly::SparsityPattern p;
  p.row_offsets = {0, 1};
  p.columns = {0};
  la::Matrix J(p);
  la::NonlinearSolver snes(
      J, [](std::span<const double> u, std::span<double> r) { r[0] = u[0] * u[0] + 1.0; },
      [](std::span<const double> u, la::Matrix& Jm) {
        const Index row[1] = {0};
        const double d[1] = {2 * u[0] + (u[0] == 0.0 ? 1e-3 : 0.0)};
        Jm.add(row, row, d);
      },
      1e-10, 1e-12, 20, "test_noroot_");
  la::Vector u(1, 1);
  u.set_all(0.7);
  const auto rep = snes.solve(u);
  EXPECT_FALSE(rep.converged);
  EXPECT_FALSE(rep.reason.empty());
}

}  // namespace
}  // namespace perimorph
