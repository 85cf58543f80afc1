// la::Matrix insertion: the direct CSR path (one process) gives exactly the
// sums MatSetValues(ADD_VALUES) and a dense accumulation give, in the same
// order (bit for bit); negative indices are skipped; an entry outside the
// preallocated pattern is an error that names it; the matrix stays usable
// across finalize / add / mult phases.

#include "perimorph/la/matrix.hpp"
#include "perimorph/assembly/nonlocal_assembly.hpp"
#include "perimorph/assembly/sparsity.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/setup/discretization.hpp"
#include "support/cases.hpp"
#include "support/dense_inserter.hpp"

#include <gtest/gtest.h>

#include <cstring>

namespace perimorph {
namespace {

assembly::SparsityPattern two_by_two_blocks() {
  // 3 block rows of size 2; block row 0 couples with 0, 1; row 1 with 0, 1, 2; row 2 with 1, 2.
  assembly::SparsityPattern p;
  p.block_size = 2;
  p.row_offsets = {0, 2, 5, 7};
  p.columns = {0, 1, 0, 1, 2, 1, 2};
  return p;
}

TEST(LaMatrix, DirectInsertionEqualsDenseAccumulationBitwise) {
  auto c = testing::box_case(3, {5, 5, 5}, Vec3::Ones(), 90.0, 0.25);
  testing::add_nonlocal(c, casefile::KernelKind::exponential, 0.5, 0.1, 2);
  c.alpha.regions = {testing::alpha_ball(Vec3::Constant(0.5), 0.15, 0.2)};
  const auto m = setup::build_discretization(c);
  const auto& nl = *m.nonlocal;
  const assembly::NonlocalSpace space{m.mesh, m.dofmap, nl.points, nl.graph, nl.kernel};
  la::Matrix K(assembly::build_sparsity(m.dofmap, &nl.graph));
  testing::DenseInserter D(m.dofmap.num_dofs());
  assembly::assemble_nonlocal(space, K);
  assembly::assemble_nonlocal(space, D);
  K.finalize();
  const Eigen::MatrixXd A = K.to_dense();
  ASSERT_EQ(A.rows(), D.A.rows());
  EXPECT_GT(D.A.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(std::memcmp(A.data(), D.A.data(), sizeof(double) * static_cast<std::size_t>(A.size())), 0);
}

TEST(LaMatrix, NegativeIndicesSkippedOutsidePatternIsAnError) {
  la::Matrix K(two_by_two_blocks());
  const std::vector<Index> rows{0, -1, 3}, cols{1, 2, -1};
  const std::vector<double> v{1, 2, 3, 4, 5, 6, 7, 8, 9};
  K.add(rows, cols, v);
  K.finalize();
  const Eigen::MatrixXd A = K.to_dense();
  EXPECT_EQ(A(0, 1), 1.0);
  EXPECT_EQ(A(0, 2), 2.0);
  EXPECT_EQ(A(3, 1), 7.0);
  EXPECT_EQ(A(3, 2), 8.0);
  EXPECT_EQ(A.cwiseAbs().sum(), 18.0);
  // Block rows 0 and 2 do not couple: entry (0, 4) is outside the pattern.
  const std::vector<Index> r0{0}, c4{4};
  const std::vector<double> one{1.0};
  try {
    K.add(r0, c4, one);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("(0, 4)"), std::string::npos) << e.what();
  }
}

TEST(LaMatrix, PhasesAddFinalizeMultAdd) {
  la::Matrix K(two_by_two_blocks());
  const std::vector<Index> idx{2, 3};
  const std::vector<double> v{2, 0, 0, 2};
  K.add(idx, idx, v);
  K.finalize();
  la::Vector x(6, 2), y(6, 2);
  x.assign(std::vector<double>{0, 0, 1, 1, 0, 0});
  K.mult(x, y);
  EXPECT_EQ(y.to_std()[2], 2.0);
  K.add(idx, idx, v);  // a second insertion phase
  K.finalize();
  K.mult(x, y);
  EXPECT_EQ(y.to_std()[3], 4.0);
  la::Matrix copy = K.duplicate();
  copy.add(idx, idx, v);
  copy.finalize();
  EXPECT_EQ(copy.to_dense()(2, 2), 6.0);
  EXPECT_EQ(K.to_dense()(2, 2), 4.0);
}

}  // namespace
}  // namespace perimorph
