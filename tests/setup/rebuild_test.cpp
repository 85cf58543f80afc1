// A discretization rebuilt for a new α (setup/discretization.hpp,
// rebuild_for_alpha; THEORY §5, α grows during a run): the same α gives the
// same model; another α gives exactly what building the case with that α
// gives (points, graph, morphed C, CG/DG flags, dofs, K), and failed bonds,
// keyed by cell and point, carry over to it.

#include "perimorph/bonds/broken_bonds.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/setup/nonlocal_setup.hpp"
#include "perimorph/system/stiffness.hpp"
#include "support/fracture_cases.hpp"

#include <gtest/gtest.h>

namespace perimorph {
namespace {

/// The pulled plate of the fracture tests, DG where purely non-local, with
/// α = 1 in the strip lo ≤ x ≤ hi.
casefile::CaseConfig strip(double lo, double hi) {
  auto c = testing::pulled_case(2, {1.0}, 1e-3);
  c.nonlocal.discretization = casefile::Discretization::discontinuous;
  c.alpha.regions.front().lower.x() = lo;
  c.alpha.regions.front().upper.x() = hi;
  return c;
}

Index dg_cells(const setup::Discretization& d) {
  Index n = 0;
  for (Index c = 0; c < d.mesh.num_cells(); ++c) n += d.dofmap.continuity(c) != dofs::Continuity::continuous;
  return n;
}

void expect_same(const setup::Discretization& a, const setup::Discretization& b,
                 const bonds::BrokenBonds* failed = nullptr) {
  ASSERT_EQ(a.dofmap.num_dofs(), b.dofmap.num_dofs());
  for (Index c = 0; c < a.mesh.num_cells(); ++c) {
    ASSERT_EQ(a.dofmap.continuity(c), b.dofmap.continuity(c)) << "cell " << c;
    const auto na = a.dofmap.cell_nodes(c), nb = b.dofmap.cell_nodes(c);
    ASSERT_TRUE(std::equal(na.begin(), na.end(), nb.begin(), nb.end())) << "cell " << c;
  }
  EXPECT_EQ(a.nonlocal->points.x, b.nonlocal->points.x);
  EXPECT_EQ(a.nonlocal->points.cell_alpha_max, b.nonlocal->points.cell_alpha_max);
  EXPECT_EQ(a.nonlocal->graph.num_pairs(), b.nonlocal->graph.num_pairs());
  EXPECT_EQ(a.nonlocal->morph.purely_nonlocal, b.nonlocal->morph.purely_nonlocal);
  const Eigen::MatrixXd Ka = system::assemble_stiffness(a, failed).K.to_dense();
  const Eigen::MatrixXd Kb = system::assemble_stiffness(b, failed).K.to_dense();
  EXPECT_EQ((Ka - Kb).cwiseAbs().maxCoeff(), 0.0) << "K differs";
}

TEST(RebuildForAlpha, TheSameAlphaGivesTheSameModel) {
  const auto c = strip(1.5, 2.5);
  const auto d = setup::build_discretization(c);
  expect_same(setup::rebuild_for_alpha(d, setup::make_alpha_field(c)), d);
}

TEST(RebuildForAlpha, AWiderZoneEqualsBuildingWithItAndKeepsFailedBonds) {
  const auto narrow = setup::build_discretization(strip(1.5, 2.5));
  const auto wide_case = strip(1.0, 3.0);
  const auto wide = setup::build_discretization(wide_case);
  const auto rebuilt = setup::rebuild_for_alpha(narrow, setup::make_alpha_field(wide_case));
  std::printf("DG cells: narrow %d, wide %d, rebuilt %d; dofs %d -> %d\n", dg_cells(narrow), dg_cells(wide),
              dg_cells(rebuilt), narrow.dofmap.num_dofs(), rebuilt.dofmap.num_dofs());
  ASSERT_GT(dg_cells(wide), dg_cells(narrow)) << "no cell switched to DG: the test would be vacuous";
  expect_same(rebuilt, wide);
  // Kept, not recomputed: the mesh, the quadrature, the calibrated kernel.
  EXPECT_EQ(rebuilt.mesh.num_nodes(), narrow.mesh.num_nodes());
  EXPECT_EQ(rebuilt.nonlocal->kernel.scale, narrow.nonlocal->kernel.scale);
  EXPECT_EQ(rebuilt.nonlocal->calibration.gc_factor, narrow.nonlocal->calibration.gc_factor);
  // Failed bonds (cell, point) of the narrow model carry over: some bonds of
  // the middle cells, which both zones hold.
  bonds::BrokenBonds failed(narrow.mesh.num_cells(), narrow.nonlocal->points.per_cell);
  const auto& graph = narrow.nonlocal->graph;
  for (Index e = 0; e < narrow.mesh.num_cells(); ++e) {
    const double x = narrow.mesh.cell_centroid(e).x();
    if (x < 1.9 || x > 2.1) continue;
    for (const Index f : graph.row(e))
      if (f > e) failed.add({e, f, 0, 1});
  }
  ASSERT_GT(failed.size(), 10u);
  expect_same(rebuilt, wide, &failed);
  const Eigen::MatrixXd intact = system::assemble_stiffness(rebuilt).K.to_dense();
  EXPECT_GT((intact - system::assemble_stiffness(rebuilt, &failed).K.to_dense()).cwiseAbs().maxCoeff(), 0.0)
      << "the failed bonds changed nothing: the check would be vacuous";
}

}  // namespace
}  // namespace perimorph
