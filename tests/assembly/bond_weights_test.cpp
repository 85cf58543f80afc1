// Bond weights per non-local point (bond_stretch.hpp, the damage index of
// THEORY §5): every bond counts at both its points, failed bonds also in
// `lost`, the sums are the same for one and two threads, a part's cells get
// the whole pass's sums, and so does the damage index of a list of cells.

#include "perimorph/assembly/bond_stretch.hpp"
#include "perimorph/bonds/broken_bonds.hpp"
#include "perimorph/bonds/nonlocal_points.hpp"
#include "perimorph/partition/partition.hpp"
#include "perimorph/setup/discretization.hpp"
#include "support/cases.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace perimorph {
namespace {

TEST(BondWeights, EveryBondCountsAtBothPointsForAnyThreadCount) {
  auto c = testing::box_case(2, {16, 8, 1}, Vec3(4.0, 2.0, 1.0), 1.0, 0.25);
  testing::add_nonlocal(c, casefile::KernelKind::gaussian, 0.375, 0.125, 2,
                        casefile::Discretization::discontinuous);
  casefile::AlphaRegionSpec r;
  r.shape = casefile::AlphaShapeKind::box;
  r.lower = Vec3(1.5, -1.0, 0.0);
  r.upper = Vec3(2.5, 3.0, 0.0);
  r.transition = 0.75;
  c.alpha.regions = {r};
  c.materials[0].nu = std::numeric_limits<double>::quiet_NaN();
  const auto model = setup::build_discretization(c);
  const auto& nl = *model.nonlocal;
  assembly::NonlocalSpace space{model.mesh, model.dofmap, nl.points, nl.graph, nl.kernel};
  // Every bond (s = 0 > −∞ at u = 0), and as failed those crossing x = 2.
  const std::vector<double> zero(static_cast<std::size_t>(model.dofmap.num_dofs()), 0.0);
  const auto all = assembly::bonds_over(space, zero, -std::numeric_limits<double>::infinity());
  bonds::BrokenBonds broken(model.mesh.num_cells(), nl.points.per_cell);
  double total = 0.0, lost = 0.0;
  for (const auto& b : all) {
    const double v = b.k * std::pow(b.xi.squaredNorm(), 2);  // W ᾱ c |ξ|²
    total += v;
    const double xg = nl.points.x[nl.points.index(b.id.e, b.id.g)].x();
    const double xh = nl.points.x[nl.points.index(b.id.f, b.id.h)].x();
    if ((xg < 2.0) != (xh < 2.0)) {
      broken.add(b.id);
      lost += v;
    }
  }
  ASSERT_GT(broken.size(), 50u);
  space.broken = &broken;
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const auto one = assembly::point_bond_weights(space);
  omp_set_num_threads(2);
  const auto two = assembly::point_bond_weights(space);
  omp_set_num_threads(saved);
  EXPECT_EQ(one.total, two.total);
  EXPECT_EQ(one.lost, two.lost);
  const double sum_total = std::accumulate(one.total.begin(), one.total.end(), 0.0);
  const double sum_lost = std::accumulate(one.lost.begin(), one.lost.end(), 0.0);
  EXPECT_NEAR(sum_total, 2.0 * total, 1e-12 * total);
  EXPECT_NEAR(sum_lost, 2.0 * lost, 1e-12 * lost);
  for (std::size_t k = 0; k < one.total.size(); ++k) EXPECT_LE(one.lost[k], one.total[k]);

  // A part's cells (a process's piece, issue 17): the same bits at their
  // points, nothing at the others'; the parts together are every point.
  for (int parts : {2, 3}) {
    std::vector<int> seen(one.total.size(), 0);
    for (int q = 0; q < parts; ++q) {
      const auto cells = partition::cells_of_part(model.mesh, parts, q);
      const auto mine = assembly::point_bond_weights(space, cells);
      for (Index e = 0; e < model.mesh.num_cells(); ++e)
        for (int g = 0; g < nl.points.per_cell; ++g) {
          const std::size_t k = nl.points.index(e, g);
          const bool flagged = cells[static_cast<std::size_t>(e)] != 0;
          seen[k] += flagged ? 1 : 0;
          EXPECT_EQ(mine.total[k], flagged ? one.total[k] : 0.0) << parts << " " << e;
          EXPECT_EQ(mine.lost[k], flagged ? one.lost[k] : 0.0) << parts << " " << e;
        }
    }
    EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int n) { return n == 1; })) << parts;
  }

  // The damage index of listed cells (the output's cells, issue 17): the
  // mean of lost / total over each cell's points, the same bits as from the
  // whole arrays, in the list's order, for one and two threads.
  std::vector<Index> listed;
  for (Index e = model.mesh.num_cells() - 1; e >= 0; e -= 3) listed.push_back(e);
  omp_set_num_threads(1);
  const auto d1 = assembly::cell_damage(space, listed);
  omp_set_num_threads(2);
  const auto d2 = assembly::cell_damage(space, listed);
  omp_set_num_threads(saved);
  ASSERT_EQ(d1.size(), listed.size());
  EXPECT_EQ(d1, d2);
  std::size_t damaged = 0;
  for (std::size_t k = 0; k < listed.size(); ++k) {
    double d = 0.0;
    for (int g = 0; g < nl.points.per_cell; ++g) {
      const std::size_t i = nl.points.index(listed[k], g);
      d += one.total[i] > 0.0 ? one.lost[i] / one.total[i] : 0.0;
    }
    EXPECT_EQ(d1[k], d / nl.points.per_cell) << listed[k];
    damaged += d1[k] > 0.0 ? 1 : 0;
  }
  EXPECT_GT(damaged, 0u);
  EXPECT_LT(damaged, listed.size());
}

}  // namespace
}  // namespace perimorph
