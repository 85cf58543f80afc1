// Bond failure's decisions shared between processes (evolution/bond_decisions.hpp)
// under mpiexec -n 1, 2 and 3: the fraction rule (break the bonds within a
// fraction of the largest stretch) takes the largest stretch over the whole
// model, not each process's own.

#include "perimorph/casefile/parse_case.hpp"
#include "perimorph/evolution/bond_failure.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/partition/partition.hpp"
#include "perimorph/run/static_run.hpp"
#include "perimorph/setup/critical_stretch.hpp"
#include "perimorph/setup/piece_model.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace perimorph {
namespace {

TEST(DistributedBondFailure, TheFractionRuleTakesTheLargestStretchOverTheModel) {
  casefile::CaseConfig config =
      casefile::parse_case_file(std::string(PERIMORPH_SOURCE_DIR) + "/examples/fracture_plate_2d/case.toml");
  config.adaptivity.enabled = false;
  const setup::Discretization part = run::process_part(config);
  const auto owner = partition::coordinate_bisection(part.mesh, la::world_size()).owner;
  const setup::Discretization piece =
      setup::cut_to_piece(part, owner, la::world_rank(), la::any_over_processes);
  // u_x = a x |x|: the stretch grows along x, its largest at the far end (one process's cells).
  double length = 0.0;
  for (Index n = 0; n < part.mesh.num_nodes(); ++n)
    length = std::max(length, std::abs(part.mesh.node(n).x()));
  evolution::RunState state(piece);
  const double a = 1.5 * setup::critical_stretch(piece) / length;
  for (Index n = 0; n < piece.dofmap.num_nodes(); ++n) {
    const Vec3 x = piece.dofmap.node_coordinate(piece.mesh, n);
    state.u[static_cast<std::size_t>(n * piece.dim())] = a * x.x() * std::abs(x.x());
  }
  ASSERT_EQ(piece.config.fracture.rule, casefile::BreakRule::all);
  const auto over = evolution::BondFailure(piece).select(state);

  setup::Discretization with_fraction = piece;
  with_fraction.config.fracture.rule = casefile::BreakRule::fraction;
  with_fraction.config.fracture.fraction = 0.9;
  const auto got = evolution::BondFailure(with_fraction).select(state);

  std::vector<double> stretches;
  for (const auto& b : over) stretches.push_back(b.stretch);
  const std::vector<double> all = la::all_gather(stretches);
  ASSERT_FALSE(all.empty());
  const double bar = 0.9 * *std::max_element(all.begin(), all.end());
  std::vector<assembly::StretchedBond> expected;
  for (const auto& b : over)
    if (b.stretch >= bar) expected.push_back(b);
  // Every collective before any assertion: a process that stops early must not leave the others waiting.
  const std::vector<double> kept = la::all_gather({static_cast<double>(got.size())});
  ASSERT_EQ(got.size(), expected.size()) << "process " << la::world_rank();
  for (std::size_t k = 0; k < got.size(); ++k) {
    EXPECT_TRUE(got[k].id.e == expected[k].id.e && got[k].id.f == expected[k].id.f &&
                got[k].id.g == expected[k].id.g && got[k].id.h == expected[k].id.h)
        << k;
    EXPECT_EQ(got[k].stretch, expected[k].stretch) << k;
  }
  // Some bonds over s_crit are not kept, and on several processes some
  // process keeps none of its own (its stretches are below the bar).
  double total = 0.0;
  for (double k : kept) total += k;
  EXPECT_GT(total, 0.0);
  EXPECT_LT(total, static_cast<double>(all.size()));
  if (la::world_size() > 1) {
    EXPECT_EQ(*std::min_element(kept.begin(), kept.end()), 0.0);
  }
}

}  // namespace
}  // namespace perimorph
