// The evolution-component interface on its own (evolution/component.hpp):
// inspect proposes and changes nothing; apply changes the state and the
// system and says how; a component that has applied is quiet at the same
// state. Bond failure (a downdate) and the support of parts cut free (quiet
// while nothing is cut loose; tests/evolution/floating_parts_test.cpp holds
// parts) are the two components of a fracture run.

#include "perimorph/evolution/bond_failure.hpp"
#include "perimorph/evolution/part_support.hpp"
#include "perimorph/run/static_run.hpp"
#include "perimorph/setup/boundary_conditions.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/system/stiffness.hpp"
#include "support/fracture_cases.hpp"

#include <gtest/gtest.h>

namespace perimorph {
namespace {

struct Fixture {
  setup::Discretization disc;
  system::ConstrainedSystem sys;
  evolution::RunState state;

  explicit Fixture(const casefile::CaseConfig& c)
      : disc(setup::build_discretization(c)),
        sys(disc, system::assemble_stiffness(disc).K, setup::build_dirichlet(disc),
            setup::build_external_force(disc)),
        state(disc) {
    // A kink across x = 2.03: the bonds across it stretch most.
    for (Index a = 0; a < disc.dofmap.num_nodes(); ++a) {
      const Vec3 x = disc.dofmap.node_coordinate(disc.mesh, a);
      state.u[static_cast<std::size_t>(a * 2)] = 0.5e-3 * x.x() + (x.x() > 2.03 ? 2e-3 : 0.0);
    }
  }
};

TEST(EvolutionComponent, BondFailureInspectsWithoutChangingAndAppliesADowndate) {
  Fixture f(testing::pulled_case(2, {1.0}, 1e-3));
  evolution::BondFailure failure(f.disc);
  EXPECT_EQ(failure.name(), "bond failure");
  const Eigen::MatrixXd K0 = f.sys.K().to_dense();
  const evolution::Proposal p = failure.inspect(f.state, f.sys);
  ASSERT_GT(p.changes, 10u);
  EXPECT_EQ(p.changes, failure.select(f.state).size());
  EXPECT_EQ(p.changes, failure.proposed().size());
  EXPECT_TRUE(f.state.failed.empty()) << "inspect changed the state";
  EXPECT_EQ(f.state.energy.dissipated, 0.0);
  EXPECT_EQ((f.sys.K().to_dense() - K0).cwiseAbs().maxCoeff(), 0.0) << "inspect changed the system";
  EXPECT_EQ(failure.inspect(f.state, f.sys).changes, p.changes) << "a second inspect proposes the same";

  EXPECT_EQ(failure.apply(f.state, f.sys), evolution::Effect::downdate);
  EXPECT_EQ(f.state.failed.size(), p.changes);
  EXPECT_EQ(f.state.failed_in_order.size(), p.changes);
  EXPECT_GT(f.state.energy.dissipated, 0.0);
  EXPECT_EQ(f.state.energy.dissipated, failure.applied_energy().dissipated);
  EXPECT_EQ(f.state.energy.overshoot, failure.applied_energy().overshoot);
  EXPECT_FALSE(f.sys.last_downdated().empty());
  EXPECT_GT((f.sys.K().to_dense() - K0).cwiseAbs().maxCoeff(), 0.0);
  double per_cell = 0.0;
  for (const auto& [c, v] : f.state.cell_dissipated) per_cell += v;
  EXPECT_NEAR(per_cell, f.state.energy.dissipated, 1e-12 * per_cell);
  // At the same displacement the failed bonds are gone and the rest were
  // under the criterion: quiet.
  EXPECT_TRUE(failure.inspect(f.state, f.sys).quiet());
}

TEST(EvolutionComponent, PartSupportIsQuietUntilBondsFailAndLooksAtEachFailureOnce) {
  Fixture f(testing::pulled_case(2, {1.0}, 1e-3));
  evolution::BondFailure failure(f.disc);
  evolution::PartSupport support(f.disc);
  EXPECT_TRUE(support.inspect(f.state, f.sys).quiet()) << "nothing has failed";
  ASSERT_FALSE(failure.inspect(f.state, f.sys).quiet());
  failure.apply(f.state, f.sys);
  // The kink fails bonds in the non-local middle only: no dof loses all its
  // stiffness and no part is cut free (the local cells around hold it).
  EXPECT_TRUE(support.inspect(f.state, f.sys).quiet());
  EXPECT_TRUE(f.state.held_dofs.empty());
  EXPECT_EQ(f.state.floating_parts, 0u);
  EXPECT_TRUE(support.inspect(f.state, f.sys).quiet());
}

TEST(EvolutionComponent, RunSetupOrdersTheFractureComponents) {
  const auto with = setup::build_discretization(testing::pulled_case(2, {1.0}, 1e-3));
  const auto set = run::prepare_run(with);
  ASSERT_EQ(set.components.size(), 2u);
  EXPECT_EQ(set.components[0]->name(), "bond failure");
  EXPECT_EQ(set.components[1]->name(), "support of parts cut free");
  auto c = testing::pulled_case(2, {1.0}, 1e-3);
  c.fracture.enabled = false;
  EXPECT_TRUE(run::prepare_run(setup::build_discretization(c)).components.empty());
}

}  // namespace
}  // namespace perimorph
