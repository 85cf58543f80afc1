// A constrained system carried over to a grown α (system/remodel.hpp,
// THEORY §5): cells switch from CG to DG and new cell pairs interact; the
// remodelled K, A and right-hand side equal those assembled from the new
// discretization (failed bonds left out of both), and the carried-over
// displacement is the same field.

#include "perimorph/system/remodel.hpp"
#include "perimorph/bonds/broken_bonds.hpp"
#include "perimorph/setup/boundary_conditions.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/setup/nonlocal_setup.hpp"
#include "perimorph/system/constrained_system.hpp"
#include "perimorph/system/stiffness.hpp"
#include "support/fracture_cases.hpp"

#include <gtest/gtest.h>

#include <cstdio>

namespace perimorph {
namespace {

/// The pulled plate of the fracture tests, DG where purely non-local, α = 1
/// on 1.5 ≤ x ≤ 2.5 with a transition 0.75 wide.
casefile::CaseConfig plate() {
  auto c = testing::pulled_case(2, {1.0}, 1e-3);
  c.nonlocal.discretization = casefile::Discretization::discontinuous;
  return c;
}

system::ConstrainedSystem make_system(const setup::Discretization& d, const bonds::BrokenBonds* failed) {
  return system::ConstrainedSystem(d, system::assemble_stiffness(d, failed).K, setup::build_dirichlet(d),
                                   setup::build_external_force(d));
}

/// α of `d` with a ball of α = 1 (radius r, transition 0.375) at (3.2, 1).
alpha::AlphaField grown(const setup::Discretization& d, double r = 0.6) {
  return d.nonlocal->alpha.grown({{alpha::Ball{Vec3(3.2, 1.0, 0.0), r}, 0.375, alpha::Profile::cubic}}, 2);
}

double max_abs(const Eigen::MatrixXd& m) {
  return m.cwiseAbs().maxCoeff();
}

/// Remodels the plate's system to α grown by a ball of radius r and compares
/// it with the system assembled for the grown model.
void check_remodel(double radius, bool partial) {
  const auto before = setup::build_discretization(plate());
  const auto after = setup::rebuild_for_alpha(before, grown(before, radius));
  ASSERT_GT(after.dofmap.num_dofs(), before.dofmap.num_dofs()) << "no cell switched to DG";
  bonds::BrokenBonds failed(before.mesh.num_cells(), before.nonlocal->points.per_cell);
  for (Index e = 0; e < before.mesh.num_cells(); ++e) {
    const double x = before.mesh.cell_centroid(e).x();
    if (x < 1.9 || x > 2.1) continue;
    for (const Index f : before.nonlocal->graph.row(e))
      if (f > e) failed.add({e, f, 1, 0});
  }
  ASSERT_GT(failed.size(), 10u);

  auto sys = make_system(before, &failed);
  auto r = system::remodel(sys, before, after, &failed, setup::build_dirichlet(after),
                           setup::build_external_force(after));
  std::printf("%zu of %d cells changed, dofs %d -> %d, %s update\n", r.cells.size(), before.mesh.num_cells(),
              before.dofmap.num_dofs(), after.dofmap.num_dofs(), r.partial ? "partial" : "full");
  EXPECT_EQ(r.partial, partial) << "not the update meant to be tested";
  ASSERT_GT(r.cells.size(), 0u);
  if (partial) {
    EXPECT_LT(r.cells.size(), static_cast<std::size_t>(before.mesh.num_cells()) / 2) << "not a local update";
  }
  const auto ref = make_system(after, &failed);
  const Eigen::MatrixXd K = r.system->K().to_dense(), K_ref = ref.K().to_dense();
  const double scale = max_abs(K_ref);
  const double dK = max_abs(K - K_ref) / scale;
  const double dA = max_abs(r.system->A().to_dense() - ref.A().to_dense()) / scale;
  const auto r1 = r.system->rhs_unit().to_std(), r2 = ref.rhs_unit().to_std();
  double dr = 0.0, rmax = 0.0;
  for (std::size_t k = 0; k < r1.size(); ++k) {
    dr = std::max(dr, std::abs(r1[k] - r2[k]));
    rmax = std::max(rmax, std::abs(r2[k]));
  }
  std::printf("remodelled vs assembled: K %.2e, A %.2e, rhs %.2e (relative)\n", dK, dA, dr / rmax);
  EXPECT_LE(dK, 1e-12);
  EXPECT_LE(dA, 1e-12);
  EXPECT_LE(dr, 1e-12 * rmax);
  // The reference diagonal is carried over: positive on every free dof.
  const auto& diag = r.system->reference_diagonal();
  for (Index d = 0; d < after.dofmap.num_dofs(); ++d)
    if (!r.system->prescribed(d)) {
      EXPECT_GT(diag[static_cast<std::size_t>(d)], 0.0) << "dof " << d;
    }
}

TEST(Remodel, GrownAlphaWithCellsSwitchingToDGGivesTheAssembledSystem) {
  check_remodel(0.6, true);
}

TEST(Remodel, ALargeGrowthIsAssembledAnewAndGivesTheSameSystem) {
  check_remodel(3.0, false);
}

TEST(Remodel, CarriedDisplacementIsTheSameField) {
  const auto before = setup::build_discretization(plate());
  const auto after = setup::rebuild_for_alpha(before, grown(before));
  ASSERT_GT(after.dofmap.num_dofs(), before.dofmap.num_dofs());
  // A smooth, non-linear field at the dof nodes: the DG copies take the CG values.
  auto field = [](const Vec3& x, int k) {
    return k == 0 ? 1e-3 * x.x() * x.x() + 0.2 : std::sin(x.x()) * x.y();
  };
  std::vector<double> u(static_cast<std::size_t>(before.dofmap.num_dofs()));
  for (Index n = 0; n < before.dofmap.num_nodes(); ++n)
    for (int k = 0; k < 2; ++k)
      u[static_cast<std::size_t>(2 * n + k)] = field(before.dofmap.node_coordinate(before.mesh, n), k);
  const auto v = system::transfer_dof_vector(before, after, u);
  for (Index n = 0; n < after.dofmap.num_nodes(); ++n)
    for (int k = 0; k < 2; ++k)
      ASSERT_EQ(v[static_cast<std::size_t>(2 * n + k)], field(after.dofmap.node_coordinate(after.mesh, n), k))
          << "node " << n;
}

TEST(Remodel, SameAlphaChangesNoCell) {
  const auto before = setup::build_discretization(plate());
  const auto same = setup::rebuild_for_alpha(before, before.nonlocal->alpha);
  EXPECT_TRUE(system::changed_cells(before, same).empty());
}

}  // namespace
}  // namespace perimorph
