// Reassembly in place of the cells where α changed
// (system::ConstrainedSystem::reassemble, THEORY §3–§4): K, A and the
// right-hand side equal those of a system built from the new discretization,
// with failed bonds left out; a change of the dofs (CG ↔ DG) is refused.

#include "perimorph/bonds/broken_bonds.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/setup/boundary_conditions.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/setup/nonlocal_setup.hpp"
#include "perimorph/system/constrained_system.hpp"
#include "perimorph/system/remodel.hpp"
#include "perimorph/system/stiffness.hpp"
#include "support/fracture_cases.hpp"

#include <gtest/gtest.h>

namespace perimorph {
namespace {

/// The pulled plate of the fracture tests (CG everywhere unless `dg`) with
/// α = 1 on lo ≤ x ≤ hi and a cubic transition `t` wide.
casefile::CaseConfig strip(double lo, double hi, double t, bool dg = false) {
  auto c = testing::pulled_case(2, {1.0}, 1e-3);
  if (dg) c.nonlocal.discretization = casefile::Discretization::discontinuous;
  auto& r = c.alpha.regions.front();
  r.lower.x() = lo;
  r.upper.x() = hi;
  r.transition = t;
  return c;
}

system::ConstrainedSystem make_system(const setup::Discretization& d, const bonds::BrokenBonds* failed) {
  return system::ConstrainedSystem(d, system::assemble_stiffness(d, failed).K, setup::build_dirichlet(d),
                                   setup::build_external_force(d));
}

TEST(Reassemble, CellsWhereAlphaChangedGiveTheNewSystem) {
  // The same support of α (0.75 ≤ x ≤ 3.25), a narrower α = 1 core: the same
  // cell graph and dofs, other point α and morphed C.
  const auto before = setup::build_discretization(strip(1.5, 2.5, 0.75));
  const auto after_case = strip(1.6, 2.4, 0.85);
  const auto after = setup::rebuild_for_alpha(before, setup::make_alpha_field(after_case));
  ASSERT_EQ(after.dofmap.num_dofs(), before.dofmap.num_dofs());
  const std::vector<Index> cells = system::changed_cells(before, after);
  std::printf("%zu of %d cells changed\n", cells.size(), before.mesh.num_cells());
  ASSERT_GT(cells.size(), 0u);
  ASSERT_LT(cells.size(), static_cast<std::size_t>(before.mesh.num_cells())) << "not a local update";
  // Some failed bonds in the middle, left out of both.
  bonds::BrokenBonds failed(before.mesh.num_cells(), before.nonlocal->points.per_cell);
  for (Index e = 0; e < before.mesh.num_cells(); ++e) {
    const double x = before.mesh.cell_centroid(e).x();
    if (x < 1.9 || x > 2.1) continue;
    for (const Index f : before.nonlocal->graph.row(e))
      if (f > e) failed.add({e, f, 1, 0});
  }
  ASSERT_GT(failed.size(), 10u);

  auto sys = make_system(before, &failed);
  sys.reassemble(before, after, cells, &failed);
  const auto ref = make_system(after, &failed);
  const Eigen::MatrixXd K = sys.K().to_dense(), K_ref = ref.K().to_dense();
  const double scale = K_ref.cwiseAbs().maxCoeff();
  const Eigen::MatrixXd K_before = make_system(before, &failed).K().to_dense();
  const double change = (K_ref - K_before).cwiseAbs().maxCoeff() / scale;
  const double dK = (K - K_ref).cwiseAbs().maxCoeff() / scale;
  const double dA = (sys.A().to_dense() - ref.A().to_dense()).cwiseAbs().maxCoeff() / scale;
  const auto r1 = sys.rhs_unit().to_std(), r2 = ref.rhs_unit().to_std();
  double dr = 0.0, rmax = 0.0;
  for (std::size_t k = 0; k < r1.size(); ++k) {
    dr = std::max(dr, std::abs(r1[k] - r2[k]));
    rmax = std::max(rmax, std::abs(r2[k]));
  }
  std::printf("K changed by %.2e (relative); reassembled vs built: K %.2e, A %.2e, rhs %.2e\n", change, dK,
              dA, dr / rmax);
  EXPECT_GT(change, 1e-3) << "α's change did not change K: the check would be vacuous";
  EXPECT_LT(dK, 1e-13);
  EXPECT_LT(dA, 1e-13);
  EXPECT_LT(dr, 1e-13 * rmax);
}

TEST(Reassemble, ACellSwitchingToDGIsRefused) {
  const auto narrow = setup::build_discretization(strip(1.5, 2.5, 0.75, true));
  const auto wide = setup::rebuild_for_alpha(narrow, setup::make_alpha_field(strip(1.0, 3.0, 0.75, true)));
  auto sys = make_system(narrow, nullptr);
  std::vector<Index> all(static_cast<std::size_t>(narrow.mesh.num_cells()));
  for (Index c = 0; c < narrow.mesh.num_cells(); ++c) all[static_cast<std::size_t>(c)] = c;
  try {
    sys.reassemble(narrow, wide, all);
    FAIL() << "a change of the dofs was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("build a new constrained system"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace perimorph
