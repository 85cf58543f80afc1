// A constrained system spread over the processes (issue 17), run under
// mpiexec -n 1, 2 and 3 with distributed_mpitest.cpp: what it holds at the
// owned dofs only (the applied force, the reference diagonal) read at any dof
// from the owners, and the supports of parts cut free found with those reads
// and with the dofs left without stiffness found by their owners. The pins
// are those of the whole model's search on one process, and the errors the
// same on every process.

#include "perimorph/core/error.hpp"
#include "perimorph/evolution/bond_failure.hpp"
#include "perimorph/evolution/floating_parts.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/setup/boundary_conditions.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/system/constrained_system.hpp"
#include "perimorph/system/stiffness.hpp"
#include "support/floating_plate.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>

namespace perimorph {
namespace {

/// The run's system at load factor 1, spread over the processes as a run's.
system::ConstrainedSystem spread_system(const setup::Discretization& m) {
  return system::ConstrainedSystem(m, system::assemble_stiffness_over_processes(m).K,
                                   setup::build_dirichlet(m), setup::build_external_force(m));
}

// A system spread over the processes holds its applied force and reference
// diagonal at its owned dofs only, and reads them at any dof from their owners:
// bit for bit the whole vectors (A's diagonal gathered whole, the force as
// built), signed zeros and NaN included.
TEST(DistributedSystem, ReadsWhatItHoldsAtTheOwnedDofsAtAnyDof) {
  auto c = testing::floating_plate(false);
  c.loading.body_force = Vec3(0.3, -1.7, 0.0);
  const auto m = setup::build_discretization(c);
  const std::vector<double> F = setup::build_external_force(m);
  system::ConstrainedSystem spread(m, system::assemble_stiffness_over_processes(m).K,
                                   setup::build_dirichlet(m), F);
  const Index n = m.dofmap.num_dofs();
  const auto same_bits = [](const std::vector<double>& a, const std::vector<double>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
  };
  std::vector<Index> some;  // every third dof, last first
  for (Index d = n - 1; d >= 0; d -= 3) some.push_back(d);
  const std::vector<double> diagonal = spread.A().diagonal().to_replicated();
  std::vector<double> reference, force;
  for (Index d : some) {
    reference.push_back(diagonal[static_cast<std::size_t>(d)]);
    force.push_back(F[static_cast<std::size_t>(d)]);
  }
  EXPECT_TRUE(same_bits(spread.reference_diagonal_at(some), reference));
  EXPECT_TRUE(same_bits(spread.applied_force_at(some), force));
  EXPECT_TRUE(same_bits(spread.owned_dofs().whole(spread.reference_diagonal()), diagonal));
  EXPECT_EQ(spread.reference_diagonal().size(), spread.owned_dofs().size());

  std::vector<double> odd(spread.owned_dofs().size());
  std::vector<double> whole(static_cast<std::size_t>(n));
  for (Index d = 0; d < n; ++d)
    whole[static_cast<std::size_t>(d)] = d % 5 == 1   ? -0.0
                                         : d % 5 == 2 ? std::numeric_limits<double>::quiet_NaN()
                                                      : std::sin(static_cast<double>(d));
  for (std::size_t j = 0; j < odd.size(); ++j)
    odd[j] = whole[static_cast<std::size_t>(spread.owned_dofs().dof(j))];
  std::vector<double> expected;
  for (Index d : some) expected.push_back(whole[static_cast<std::size_t>(d)]);
  EXPECT_TRUE(same_bits(spread.owned_dofs().at(odd, some), expected));
  EXPECT_TRUE(same_bits(spread.owned_dofs().whole(odd), whole));

  // A free dof left without stiffness (its diagonal downdated to zero) is
  // found by its owner and known to every process.
  Index lost = n / 2;
  while (spread.prescribed(lost)) ++lost;
  const Index one[1] = {lost};
  const double all_of_it[1] = {diagonal[static_cast<std::size_t>(lost)]};
  EXPECT_TRUE(spread.free_dofs_without_stiffness().empty());
  spread.downdate(one, all_of_it);
  spread.finish_downdate();
  EXPECT_EQ(spread.without_stiffness(spread.last_downdated()), std::vector<Index>{lost});
  EXPECT_EQ(spread.free_dofs_without_stiffness(), std::vector<Index>{lost});
}

// The CG/DG flags' union sends only the flags set: every process gets the
// elementwise maximum.
TEST(UnionOverProcesses, EveryProcessGetsTheFlagsAnyProcessSet) {
  const int rank = la::world_rank(), size = la::world_size();
  std::vector<char> mine(1000, 0), expected(1000, 0);
  for (std::size_t k = 0; k < mine.size(); k += 3) {
    if (static_cast<int>(k % 7) % size == rank) mine[k] = 1;
    expected[k] = 1;
  }
  EXPECT_EQ(la::union_over_processes(mine), expected);
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
  const std::string what =
      testing::message_of_thrown<Error>([&] { testing::break_and_support(m, state, sys); });
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
  testing::stretch_last_column(m, state.u);
  const std::string what =
      testing::message_of_thrown<Error>([&] { testing::break_and_support(m, state, sys); });
  EXPECT_NE(what.find("with no stiffness in direction x"), std::string::npos) << what;
  EXPECT_NE(what.find("no quasi-static equilibrium"), std::string::npos) << what;
}

}  // namespace
}  // namespace perimorph
