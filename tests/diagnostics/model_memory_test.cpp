// The model's memory by stage (diagnostics/model_memory.hpp): a process's
// part holds the same whole stages as one process and less of the morphed C,
// the cell graph and the non-local points;
// the whole stages grow with the mesh, the cell graph by its rows.

#include "perimorph/diagnostics/model_memory.hpp"

#include "perimorph/bonds/cell_graph.hpp"
#include "perimorph/setup/discretization.hpp"
#include "support/cases.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace perimorph {
namespace {

casefile::CaseConfig ball(Index cells_x) {
  auto c =
      testing::box_case(3, {cells_x, 6, 6}, Vec3(0.5 * static_cast<double>(cells_x), 3.0, 3.0), 100.0, 0.25);
  testing::add_nonlocal(c, casefile::KernelKind::constant, 1.0, 0.0, 2,
                        casefile::Discretization::discontinuous);
  c.alpha.regions = {testing::alpha_ball(Vec3(1.5, 1.5, 1.5), 1.0, 0.6)};
  return c;
}

TEST(ModelMemory, APartHoldsTheWholeStagesAndLessOfTheMorphedCAndGraph) {
  // 12 × 6 × 6 cells of 0.5, α around x = 1.5: the part of x > 3 reads no point of the cells of x < 1.
  const auto whole = setup::build_discretization(ball(12));
  // The other part's flags, as the processes would share them (ModelPart).
  const auto flags = [&](std::vector<char>) { return whole.nonlocal->morph.purely_nonlocal; };
  const auto part = setup::build_discretization(ball(12), {}, {2, 1, flags});
  const auto w = diagnostics::model_memory(whole), p = diagnostics::model_memory(part);
  EXPECT_GT(w.mesh, 0u);
  EXPECT_GT(w.points, 0u);
  EXPECT_GT(w.stiffness, 0u);
  // The same whole stages, and a slot per cell saying where its points are.
  EXPECT_EQ(p.whole(), w.whole() + static_cast<std::size_t>(whole.mesh.num_cells()) * sizeof(Index));
  EXPECT_LT(p.stiffness, w.stiffness);
  EXPECT_LT(p.graph, w.graph);
  EXPECT_LT(p.points, w.points);
  // One Index per directed cell pair and per cell boundary of the rows.
  const auto& g = whole.nonlocal->graph;
  EXPECT_EQ(w.graph, (g.offsets.size() + g.neighbors.size()) * sizeof(Index));
}

TEST(ModelMemory, TheWholeStagesGrowWithTheMesh) {
  // α ≡ 1: every cell pair within reach is in the graph.
  auto nonlocal = [](Index cells_x) {
    auto c = ball(cells_x);
    c.alpha.regions.clear();
    c.alpha.value = 1.0;
    return diagnostics::model_memory(setup::build_discretization(c));
  };
  const auto m6 = nonlocal(6), m12 = nonlocal(12);
  // Twice the cells: about twice the mesh, points and graph (fewer boundary cells).
  for (auto [a, b] : {std::pair{m6.mesh, m12.mesh}, {m6.points, m12.points}, {m6.graph, m12.graph}}) {
    const double ratio = static_cast<double>(b) / static_cast<double>(a);
    EXPECT_GT(ratio, 1.7);
    EXPECT_LT(ratio, 2.3);
  }
}

}  // namespace
}  // namespace perimorph
