// The supports of parts cut free on a system spread over the processes
// (issue 17), run under mpiexec -n 1, 2 and 3 with distributed_mpitest.cpp:
// the dofs left without stiffness are found by their owners, and the forces
// and reference diagonal a search reads at other dofs come from their owners
// (ConstrainedSystem::applied_force_at, reference_diagonal_at). The pins are
// those of the whole model's search on one process, and the errors the same
// on every process.

#include "perimorph/core/error.hpp"
#include "perimorph/evolution/bond_failure.hpp"
#include "perimorph/evolution/floating_parts.hpp"
#include "perimorph/setup/boundary_conditions.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/system/constrained_system.hpp"
#include "perimorph/system/stiffness.hpp"
#include "support/floating_plate.hpp"

#include <gtest/gtest.h>

#include <string>

namespace perimorph {
namespace {

/// The run's system at load factor 1, spread over the processes as a run's.
system::ConstrainedSystem spread_system(const setup::Discretization& m) {
  return system::ConstrainedSystem(m, system::assemble_stiffness_over_processes(m).K, setup::build_dirichlet(m),
                                   setup::build_external_force(m));
}

/// The message of the Error that `act` throws ("" if none).
template <class Act>
std::string error_of(Act&& act) {
  try {
    act();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(DistributedPartSupport, TheHalfCutFreeIsPinnedAsTheWholeModelsSearchPinsIt) {
  const auto m = setup::build_discretization(testing::floating_plate(false));
  evolution::RunState state(m);
  system::ConstrainedSystem sys = spread_system(m);
  state.u = testing::jump_at_middle(m);
  ASSERT_GT(testing::break_and_support(m, state, sys), 100u);
  EXPECT_EQ(state.floating_parts, 1u);
  EXPECT_EQ(state.detached_dofs, 0u);
  EXPECT_EQ(state.cell_mechanisms, 0u);
  // The whole model's search on this process alone, the force whole.
  const std::vector<double> F = setup::build_external_force(m);
  const la::DofValuesAt force = [&](std::span<const Index> dofs) {
    std::vector<double> v;
    for (Index d : dofs) v.push_back(F[static_cast<std::size_t>(d)]);
    return v;
  };
  const auto whole = evolution::find_floating_parts(
      m, evolution::stiffness_links(m, evolution::BondFailure(m).space(state)), sys.bc().dofs, force);
  ASSERT_EQ(whole.parts, 1);
  EXPECT_EQ(state.held_dofs, whole.pins);
}

TEST(DistributedPartSupport, AnUnbalancedPartCutFreeStopsEveryProcess) {
  const auto m = setup::build_discretization(testing::floating_plate(true));
  evolution::RunState state(m);
  system::ConstrainedSystem sys = spread_system(m);
  state.u = testing::jump_at_middle(m);
  const std::string what = error_of([&] { testing::break_and_support(m, state, sys); });
  EXPECT_NE(what.find("no quasi-static equilibrium"), std::string::npos) << what;
  EXPECT_NE(what.find("(2, 0, 0) and (4, 2, 0)"), std::string::npos) << what;
}

// Every bond of the last column of cells with a horizontal component fails:
// its nodes keep no stiffness along x while the traction pulls them.
TEST(DistributedPartSupport, AForceOnANodeLeftWithoutStiffnessStopsEveryProcess) {
  auto c = testing::floating_plate(true);
  c.fracture.s_crit = 1e-12;
  const auto m = setup::build_discretization(c);
  system::ConstrainedSystem sys = spread_system(m);
  evolution::RunState state(m);
  for (Index cell = 0; cell < m.mesh.num_cells(); ++cell)
    if (m.mesh.cell_centroid(cell).x() > 3.75)
      for (Index a : m.dofmap.cell_nodes(cell)) {
        const double d = m.dofmap.node_coordinate(a).x() - 3.75;
        state.u[static_cast<std::size_t>(a * 2)] = d * d;
      }
  const std::string what = error_of([&] { testing::break_and_support(m, state, sys); });
  EXPECT_NE(what.find("with no stiffness in direction x"), std::string::npos) << what;
  EXPECT_NE(what.find("no quasi-static equilibrium"), std::string::npos) << what;
}

}  // namespace
}  // namespace perimorph
