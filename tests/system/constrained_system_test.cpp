// The constrained system on its own (system/constrained_system.hpp, THEORY
// §4–§5): A is K with the prescribed dofs eliminated and the right-hand side
// takes their columns; the solution is linear in the load factor; a downdate
// by any symmetric block equals subtracting it from K and from A on free rows
// and columns, with its prescribed columns moved to the right-hand side; a dof
// left with no stiffness is found and held by a spring that carries no force.

#include "perimorph/system/constrained_system.hpp"
#include "perimorph/setup/boundary_conditions.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/system/stiffness.hpp"
#include "support/cases.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace perimorph {
namespace {

using testing::fixed;

/// A local plate [0, 2] × [0, 1], 8 × 4 cells, fixed at x = 0, pulled at
/// x = 2 by a prescribed u_x = 0.01 and by a traction on the top face.
casefile::CaseConfig plate() {
  auto c = testing::box_case(2, {8, 4, 1}, Vec3(2.0, 1.0, 1.0), 100.0, 0.25);
  c.dirichlet = {fixed("xmin", 0), fixed("xmin", 1), fixed("xmax", 0, 0.01)};
  casefile::TractionSpec t;
  t.set = "ymax";
  t.value = Vec3(0.0, 0.5, 0.0);
  c.tractions = {t};
  c.solver.rtol = 1e-12;
  return c;
}

system::ConstrainedSystem make_system(const setup::Discretization& d) {
  return system::ConstrainedSystem(d, system::assemble_stiffness(d).K, setup::build_dirichlet(d),
                                   setup::build_external_force(d));
}

Eigen::VectorXd as_eigen(const std::vector<double>& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

TEST(ConstrainedSystem, EliminatesThePrescribedDofs) {
  const auto d = setup::build_discretization(plate());
  const auto sys = make_system(d);
  const Eigen::MatrixXd K = sys.K().to_dense(), A = sys.A().to_dense();
  const Eigen::VectorXd F = as_eigen(sys.applied_force()), rhs = as_eigen(sys.rhs_unit().to_std());
  const auto n = static_cast<Index>(K.rows());
  Eigen::VectorXd g = Eigen::VectorXd::Zero(n);
  for (std::size_t k = 0; k < sys.bc().dofs.size(); ++k) g[sys.bc().dofs[k]] = sys.bc().values[k];
  ASSERT_GT(g.cwiseAbs().maxCoeff(), 0.0);
  const double scale = K.cwiseAbs().maxCoeff();
  for (Index i = 0; i < n; ++i) {
    const bool pi = sys.prescribed(i);
    for (Index j = 0; j < n; ++j) {
      const bool pj = sys.prescribed(j);
      const double expected = !pi && !pj ? K(i, j) : (i == j ? A(i, i) : 0.0);
      EXPECT_NEAR(A(i, j), expected, 1e-14 * scale) << i << ", " << j;
    }
    if (pi) {
      EXPECT_GT(A(i, i), 0.0);
      EXPECT_NEAR(rhs[i], A(i, i) * g[i], 1e-14 * scale) << "row " << i << ": u_i = g_i";
    } else {
      EXPECT_NEAR(rhs[i], F[i] - K.row(i).dot(g), 1e-12 * scale) << "row " << i;
    }
  }
}

TEST(ConstrainedSystem, SolutionIsLinearInTheLoadFactorAndBalanced) {
  const auto d = setup::build_discretization(plate());
  auto sys = make_system(d);
  sys.attach_solver();
  const Index n = d.dofmap.num_dofs();
  la::Vector u1(n, 2), u_half(n, 2);
  sys.solve(1.0, u1);
  sys.solve(0.5, u_half);
  const Eigen::VectorXd a = as_eigen(u1.to_std()), b = as_eigen(u_half.to_std());
  EXPECT_LT((a - 2.0 * b).norm(), 1e-9 * a.norm());
  // K u = F on free dofs; u = g on prescribed ones.
  const Eigen::VectorXd r = sys.K().to_dense() * a - as_eigen(sys.applied_force());
  for (Index i = 0; i < n; ++i) {
    if (sys.prescribed(i)) continue;
    EXPECT_LT(std::abs(r[i]), 1e-8) << "free dof " << i;
  }
  // The identity rows of A hold u = g to the iterative solver's tolerance
  // (rtol 1e-12; observed ≤ 4e-14 with GAMG and 2 threads), not exactly.
  for (std::size_t k = 0; k < sys.bc().dofs.size(); ++k)
    EXPECT_NEAR(a[sys.bc().dofs[k]], sys.bc().values[k], 1e-10 * 0.01);
}

TEST(ConstrainedSystem, DowndateSubtractsABlockAndMovesItsPrescribedColumns) {
  const auto d = setup::build_discretization(plate());
  auto sys = make_system(d);
  const Eigen::MatrixXd K0 = sys.K().to_dense(), A0 = sys.A().to_dense();
  const Eigen::VectorXd rhs0 = as_eigen(sys.rhs_unit().to_std());
  // The dofs of the last cell next to x = 2 (some prescribed) and a symmetric
  // block on them, a fraction of K's own entries so that the pattern holds it.
  const auto nodes = d.dofmap.cell_nodes(d.mesh.num_cells() - 1);
  std::vector<Index> dofs;
  for (Index a : nodes)
    for (int c = 0; c < 2; ++c) dofs.push_back(a * 2 + c);
  const std::size_t m = dofs.size();
  std::vector<double> block(m * m);
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t j = 0; j < m; ++j) block[i * m + j] = 0.25 * K0(dofs[i], dofs[j]);
  ASSERT_TRUE(std::any_of(dofs.begin(), dofs.end(), [&](Index k) { return sys.prescribed(k); }));
  sys.downdate(dofs, block);
  const std::vector<Index> touched = sys.finish_downdate();
  EXPECT_EQ(touched, sys.last_downdated());
  std::vector<Index> free_dofs;
  for (Index k : dofs)
    if (!sys.prescribed(k)) free_dofs.push_back(k);
  std::sort(free_dofs.begin(), free_dofs.end());
  EXPECT_EQ(touched, free_dofs);

  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(K0.rows(), K0.cols());
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t j = 0; j < m; ++j) B(dofs[i], dofs[j]) = block[i * m + j];
  Eigen::VectorXd g = Eigen::VectorXd::Zero(K0.rows());
  for (std::size_t k = 0; k < sys.bc().dofs.size(); ++k) g[sys.bc().dofs[k]] = sys.bc().values[k];
  const double scale = K0.cwiseAbs().maxCoeff();
  EXPECT_LT((sys.K().to_dense() - (K0 - B)).cwiseAbs().maxCoeff(), 1e-14 * scale);
  const Eigen::MatrixXd A = sys.A().to_dense();
  const Eigen::VectorXd rhs = as_eigen(sys.rhs_unit().to_std());
  const auto n = static_cast<Index>(K0.rows());
  for (Index i = 0; i < n; ++i) {
    for (Index j = 0; j < n; ++j) {
      const double expected = !sys.prescribed(i) && !sys.prescribed(j) ? A0(i, j) - B(i, j) : A0(i, j);
      EXPECT_NEAR(A(i, j), expected, 1e-14 * scale) << i << ", " << j;
    }
    // The block's prescribed columns: rhs_i += B_ij g_j on free rows.
    const double moved = sys.prescribed(i) ? 0.0 : B.row(i).dot(g);
    EXPECT_NEAR(rhs[i], rhs0[i] + moved, 1e-14 * scale) << "row " << i;
  }
}

TEST(ConstrainedSystem, ADofLeftWithoutStiffnessIsFoundAndHeld) {
  const auto d = setup::build_discretization(plate());
  auto sys = make_system(d);
  // A free dof in the middle of the plate: take its whole diagonal away.
  Index dof = -1;
  for (Index k = 0; k < d.dofmap.num_dofs() && dof < 0; ++k)
    if (!sys.prescribed(k) && std::abs(d.dofmap.node_coordinate(d.mesh, k / 2).x() - 1.0) < 1e-12) dof = k;
  ASSERT_GE(dof, 0);
  const double k_dd = sys.K().to_dense()(dof, dof);
  const std::vector<Index> one{dof};
  EXPECT_TRUE(sys.without_stiffness(one).empty());
  sys.downdate(one, std::vector<double>{k_dd});
  sys.finish_downdate();
  EXPECT_EQ(sys.without_stiffness(sys.last_downdated()), one);
  const Eigen::MatrixXd K_before_hold = sys.K().to_dense();
  sys.hold(one, true);
  EXPECT_DOUBLE_EQ(sys.A().to_dense()(dof, dof), k_dd) << "held by a spring of its initial stiffness";
  EXPECT_EQ(sys.rhs_unit().to_std()[static_cast<std::size_t>(dof)], 0.0);
  EXPECT_EQ((sys.K().to_dense() - K_before_hold).cwiseAbs().maxCoeff(), 0.0) << "the spring is not in K";
  EXPECT_TRUE(sys.without_stiffness(one).empty());
}

}  // namespace
}  // namespace perimorph
