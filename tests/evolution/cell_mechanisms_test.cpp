// Motions inside one cell that no intact bond resists (cell_mechanisms.hpp):
// every bond of one non-local point of a DG cell fails, the part stays
// connected, yet A turns singular (the Q1 motion that vanishes at the cell's
// other points). The support of parts cut free finds it, holds it by as many
// dofs as it has modes (2 in 2D), A is non-singular again, and the held dofs
// carry no force. A force that does work on such a motion is an error. A
// group of two cells hanging on one bond is a mechanism across cells that no
// support finds: a direct solve then fails on it, and the direct fallback
// (la::LinearSolver::allow_direct_fallback) holds its null pivots.

#include "perimorph/evolution/cell_mechanisms.hpp"
#include "perimorph/assembly/bond_stretch.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/dofs/dof_map.hpp"
#include "perimorph/evolution/bond_failure.hpp"
#include "perimorph/evolution/part_support.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/setup/boundary_conditions.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/system/stiffness.hpp"
#include "support/cases.hpp"
#include "support/floating_plate.hpp"

#include <gtest/gtest.h>
#include <Eigen/Dense>

namespace perimorph {
namespace {

using testing::constrained_system;

/// The cell whose centroid is nearest `x`.
Index cell_at(const setup::Discretization& model, const Vec3& x) {
  Index best = 0;
  for (Index c = 1; c < model.mesh.num_cells(); ++c)
    if ((model.mesh.cell_centroid(c) - x).norm() < (model.mesh.cell_centroid(best) - x).norm()) best = c;
  return best;
}

/// Fails every bond of point q of cell c (an expansion u = 1e-3 (x, y)
/// stretches them all) and runs the support of parts cut free, as the run loop does.
/// Returns the bonds failed.
std::size_t kill_point(const setup::Discretization& model, Index c, int q, evolution::RunState& state,
                       system::ConstrainedSystem& sys, bool support) {
  const auto& dm = model.dofmap;
  std::vector<double> u(static_cast<std::size_t>(dm.num_dofs()), 0.0);
  for (Index a = 0; a < dm.num_nodes(); ++a)
    for (int d = 0; d < 2; ++d)
      u[static_cast<std::size_t>(a * 2 + d)] = 1e-3 * dm.node_coordinate(model.mesh, a)[d];
  evolution::BondFailure failure(model);
  std::vector<assembly::StretchedBond> bonds = assembly::bonds_over(failure.space(state), u, 0.0);
  std::erase_if(bonds, [&](const assembly::StretchedBond& b) {
    return !((b.id.e == c && b.id.g == q) || (b.id.f == c && b.id.h == q));
  });
  state.u = u;
  failure.apply(bonds, state, sys);
  if (support) {
    evolution::PartSupport parts(model);
    if (!parts.inspect(state, sys).quiet()) parts.apply(state, sys);
  }
  return bonds.size();
}

double eigenvalue_ratio(const Eigen::MatrixXd& A) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(A, Eigen::EigenvaluesOnly);
  return eig.eigenvalues().minCoeff() / eig.eigenvalues().maxCoeff();
}

TEST(CellMechanisms, DeadPointLeavesASingularMatrix) {
  const auto model = setup::build_discretization(testing::floating_plate(false));
  evolution::RunState state(model);
  system::ConstrainedSystem sys = constrained_system(model);
  const double before = eigenvalue_ratio(sys.A().to_dense());
  EXPECT_GT(kill_point(model, cell_at(model, Vec3(2.1, 1.1, 0.0)), 3, state, sys, false), 20u);
  const double after = eigenvalue_ratio(sys.A().to_dense());
  std::printf("eigenvalue ratio of A: %.3e intact, %.3e with one point's bonds failed\n", before, after);
  EXPECT_GT(before, 1e-8);
  EXPECT_LT(std::abs(after), 1e-14);
}

TEST(CellMechanisms, DeadPointIsHeldWithoutForce) {
  const auto model = setup::build_discretization(testing::floating_plate(false));
  evolution::RunState state(model);
  system::ConstrainedSystem sys = constrained_system(model);
  kill_point(model, cell_at(model, Vec3(2.1, 1.1, 0.0)), 3, state, sys, true);
  EXPECT_EQ(state.cell_mechanisms, 1u);
  EXPECT_EQ(state.floating_parts, 0u);
  EXPECT_EQ(state.held_dofs.size(), 2u);  // the 2 modes of one point in 2D
  const Eigen::MatrixXd A = sys.A().to_dense();
  const double ratio = eigenvalue_ratio(A);
  std::printf("eigenvalue ratio of A with the cell's motion held: %.3e\n", ratio);
  EXPECT_GT(ratio, 1e-12);
  // The held dofs carry no force: K u = F there (no applied force: 0),
  // against the reactions at the pulled edge.
  const std::vector<double> rhs = sys.rhs_unit().to_std();
  const Eigen::VectorXd u = A.ldlt().solve(Eigen::Map<const Eigen::VectorXd>(rhs.data(), A.rows()));
  const Eigen::VectorXd f = sys.K().to_dense() * u;
  double reaction = 0.0;
  for (Index d : sys.bc().dofs) reaction = std::max(reaction, std::abs(f[d]));
  for (Index d : state.held_dofs) {
    std::printf("force on held dof %lld: %.3e (largest reaction %.3e)\n", static_cast<long long>(d), f[d],
                reaction);
    EXPECT_LT(std::abs(f[d]), 1e-10 * reaction);
  }
  // The free dofs are in equilibrium too.
  double residual = 0.0;
  for (Index d = 0; d < A.rows(); ++d)
    if (!sys.prescribed(d)) residual = std::max(residual, std::abs(f[d]));
  EXPECT_LT(residual, 1e-10 * reaction);
}

TEST(CellMechanisms, ForceDoingWorkOnTheMotionIsAnError) {
  const auto model = setup::build_discretization(testing::floating_plate(true));
  evolution::RunState state(model);
  system::ConstrainedSystem sys = constrained_system(model);
  // The last column of cells: the traction acts on the nodes of its right edge.
  const Index c = cell_at(model, Vec3(3.9, 1.1, 0.0));
  int q_right = 0;  // the point nearest the loaded edge
  const auto& pts = model.nonlocal->points;
  for (int q = 1; q < pts.per_cell; ++q)
    if (pts.x[pts.index(c, q)].x() > pts.x[pts.index(c, q_right)].x()) q_right = q;
  try {
    kill_point(model, c, q_right, state, sys, true);
    FAIL() << "a motion that the traction does work on was held";
  } catch (const Error& e) {
    const std::string what = e.what();
    std::printf("%s\n", what.c_str());
    EXPECT_NE(what.find("no intact bond resists"), std::string::npos) << what;
    EXPECT_NE(what.find("no quasi-static equilibrium"), std::string::npos) << what;
  }
}

// Cells A and B (neighbours inside the plate) keep their own bonds, the bonds
// between them and one bond from A to the rest; every other bond of theirs
// fails. The pair is connected (no part cut free) and each cell is held by the
// other (no motion inside one cell): the supports hold nothing. The pair can
// still turn about that bond and move across it, two modes: a Cholesky solve
// meets a zero pivot; allowed after bond failures, the fallback holds the two
// null pivots, and since no force acts on the pair the solve is exact.
TEST(CellMechanisms, PairHangingOnOneBondIsSolvedByTheDirectFallback) {
  struct Options {  // the options database is global: cleared however the test ends
    Options() {
      la::set_option("-ksp_type", "preonly");
      la::set_option("-pc_type", "cholesky");
    }
    ~Options() {
      for (const char* o : {"-ksp_type", "-pc_type"}) la::clear_option(o);
    }
  } options;
  const auto model = setup::build_discretization(testing::floating_plate(false));
  evolution::RunState state(model);
  system::ConstrainedSystem sys = constrained_system(model);
  const Index A = cell_at(model, Vec3(2.1, 1.1, 0.0)), B = cell_at(model, Vec3(2.4, 1.1, 0.0));
  const auto& dm = model.dofmap;
  std::vector<double> u(static_cast<std::size_t>(dm.num_dofs()), 0.0);
  for (Index a = 0; a < dm.num_nodes(); ++a)
    for (int d = 0; d < 2; ++d)
      u[static_cast<std::size_t>(a * 2 + d)] = 1e-3 * dm.node_coordinate(model.mesh, a)[d];
  evolution::BondFailure failure(model);
  std::vector<assembly::StretchedBond> bonds = assembly::bonds_over(failure.space(state), u, 0.0);
  auto in_pair = [&](Index c) { return c == A || c == B; };
  bool kept_one = false;
  std::erase_if(bonds, [&](const assembly::StretchedBond& b) {
    if (!in_pair(b.id.e) && !in_pair(b.id.f)) return true;  // not theirs: intact
    if (in_pair(b.id.e) && in_pair(b.id.f)) return true;    // inside the pair: intact
    if (!kept_one && (b.id.e == A || b.id.f == A)) {        // the one bond it hangs on
      kept_one = true;
      return true;
    }
    return false;
  });
  ASSERT_TRUE(kept_one);
  state.u = u;
  failure.apply(bonds, state, sys);
  evolution::PartSupport parts(model);
  EXPECT_TRUE(parts.inspect(state, sys).quiet());  // nothing the supports find
  sys.attach_solver();
  la::Vector x(dm.num_dofs(), 2);
  EXPECT_THROW(sys.solve(1.0, x), SolverError);
  sys.allow_direct_fallback();
  x.set_all(0.0);
  const la::SolveReport rep = sys.solve(1.0, x);
  std::printf("pair on one bond: %zu bonds failed; fallback %d, %d null pivots, relative residual %.2e\n",
              bonds.size(), rep.direct_fallback ? 1 : 0, rep.null_pivots, rep.relative_residual);
  EXPECT_TRUE(rep.direct_fallback);
  EXPECT_EQ(rep.null_pivots, 2);
  EXPECT_LT(rep.relative_residual, 1e-12);
}

}  // namespace
}  // namespace perimorph
