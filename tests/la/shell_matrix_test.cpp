// la::ShellMatrix (a matrix-free operator inside PETSc) with
// LinearSolver::set_operators: CG on a shell that applies a tridiagonal SPD
// matrix, preconditioned by Jacobi of an assembled matrix, reaches the
// solution of the assembled system, and the residual it reports is the
// shell's. la::Matrix::block reads a principal block; without_zero_blocks
// drops the node blocks that are all zero and keeps every value.

#include "perimorph/la/shell_matrix.hpp"
#include "perimorph/assembly/sparsity.hpp"
#include "perimorph/la/linear_solver.hpp"
#include "perimorph/la/matrix.hpp"
#include "perimorph/la/petsc_session.hpp"

#include <gtest/gtest.h>

#include <array>
#include <vector>

namespace perimorph {
namespace {

constexpr Index n = 40;

/// tridiag(−1, 2 + i/n, −1): SPD, with the full pattern of a 2-wide band
/// (the second off-diagonals stored as zeros).
la::Matrix banded() {
  assembly::SparsityPattern p;
  p.block_size = 1;
  p.row_offsets.assign(1, 0);
  for (Index r = 0; r < n; ++r) {
    for (Index c = std::max<Index>(0, r - 2); c <= std::min<Index>(n - 1, r + 2); ++c) p.columns.push_back(c);
    p.row_offsets.push_back(static_cast<Index>(p.columns.size()));
  }
  la::Matrix A(p);
  for (Index r = 0; r < n; ++r) {
    const std::array<Index, 1> row{r};
    const std::array<double, 1> d{2.0 + static_cast<double>(r) / n};
    A.add(row, row, d);
    if (r + 1 < n) {
      const std::array<Index, 1> col{r + 1};
      const std::array<double, 1> off{-1.0};
      A.add(row, col, off);
      A.add(col, row, off);
    }
  }
  A.finalize();
  return A;
}

void tridiagonal_product(std::span<const double> x, std::span<double> y) {
  for (Index r = 0; r < n; ++r) {
    const auto i = static_cast<std::size_t>(r);
    double v = (2.0 + static_cast<double>(r) / n) * x[i];
    if (r > 0) v -= x[i - 1];
    if (r + 1 < n) v -= x[i + 1];
    y[i] = v;
  }
}

struct LaShellMatrix : ::testing::Test {
  void SetUp() override {
    la::set_option("-ksp_type", "cg");
    la::set_option("-pc_type", "jacobi");
  }
  void TearDown() override {
    for (const char* o : {"-ksp_type", "-pc_type"}) la::clear_option(o);
  }
  const la::NodeCoordinate nodes = [](Index) -> Vec3 { return Vec3::Zero(); };
};

TEST_F(LaShellMatrix, KrylovOnTheShellReachesTheAssembledSolution) {
  la::Matrix P = banded();
  const la::ShellMatrix A(n, 1, tridiagonal_product);
  std::vector<double> ones(n, 1.0);
  la::Vector b(n, 1), x(n, 1), y(n, 1), xa(n, 1);
  b.assign(ones);
  A.mult(b, y);
  P.mult(b, xa);
  EXPECT_EQ(y.to_std(), xa.to_std());
  la::LinearSolver shell(1e-12, 1000);
  shell.set_operators(A, P, nodes, 1);
  const la::SolveReport rep = shell.solve(b, x);
  la::LinearSolver assembled(1e-12, 1000);
  xa.set_all(0.0);
  assembled.set_operator(P, nodes, 1);
  assembled.solve(b, xa);
  const std::vector<double> u = x.to_std(), ua = xa.to_std();
  double err = 0.0;
  for (std::size_t k = 0; k < u.size(); ++k) err = std::max(err, std::abs(u[k] - ua[k]));
  std::printf("shell: %d iterations, relative residual %.2e, |x - x_assembled| = %.2e\n", rep.iterations,
              rep.relative_residual, err);
  EXPECT_LT(rep.relative_residual, 1e-11);
  EXPECT_LT(err, 1e-10);
}

TEST(LaMatrixBlocks, BlockAndWithoutZeroBlocks) {
  const la::Matrix A = banded();
  const std::array<Index, 3> dofs{4, 5, 7};
  const Eigen::MatrixXd B = A.block(dofs);
  EXPECT_EQ(B(0, 0), 2.0 + 4.0 / n);
  EXPECT_EQ(B(0, 1), -1.0);
  EXPECT_EQ(B(1, 0), -1.0);
  EXPECT_EQ(B(1, 2), 0.0);  // (5, 7): stored zero
  EXPECT_EQ(B(2, 2), 2.0 + 7.0 / n);
  const la::Matrix C = A.without_zero_blocks();
  EXPECT_EQ(A.nonzeros(), static_cast<double>(5 * n - 6));
  EXPECT_EQ(C.nonzeros(), static_cast<double>(3 * n - 2));
  EXPECT_EQ(C.to_dense(), A.to_dense());
}

}  // namespace
}  // namespace perimorph
