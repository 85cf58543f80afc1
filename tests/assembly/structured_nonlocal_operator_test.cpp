// The matrix-free non-local operator of a structured DG0 grid
// (structured_nonlocal_operator.hpp): one block per grid offset, read from a
// small model, applied to a vector equals the assembled stiffness times it
// (3D and 2D, cells at faces, edges and corners included), its own assembly
// equals the assembled stiffness on an exact pattern, and the product is
// bit-identical for 1 and 2 threads.

#include "perimorph/assembly/structured_nonlocal_operator.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/dofs/dof_map.hpp"
#include "perimorph/mesh/mesh.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/system/stiffness.hpp"
#include "support/cases.hpp"
#include "support/dense_inserter.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace perimorph {
namespace {

/// A box of n cells of size 1 per side, DG0, α ≡ 1, pmb kernel, horizon 2.01.
casefile::CaseConfig grid(int dim, std::array<Index, 3> cells) {
  Vec3 extent(static_cast<double>(cells[0]), static_cast<double>(cells[1]), static_cast<double>(cells[2]));
  auto c = testing::box_case(dim, cells, extent, 300.0, 0.25);
  testing::add_nonlocal(c, casefile::KernelKind::pmb, 2.01, 1.0, 1,
                        casefile::Discretization::discontinuous_constant);
  c.alpha.value = 1.0;
  c.materials[0].nu = std::numeric_limits<double>::quiet_NaN();
  return c;
}

struct Fixture {
  setup::Discretization model;
  assembly::StructuredNonlocalOperator K;
};

Fixture make(int dim, std::array<Index, 3> cells) {
  const std::array<Index, 3> small_cells{7, dim > 1 ? 7 : 1, dim > 2 ? 7 : 1};
  const auto small = setup::build_discretization(grid(dim, small_cells));
  const Index centre = 3 + 7 * (dim > 1 ? 3 : 0) + 49 * (dim > 2 ? 3 : 0);
  auto model = setup::build_discretization(grid(dim, cells));
  std::vector<Index> node_of_cell;
  for (Index c = 0; c < model.mesh.num_cells(); ++c) node_of_cell.push_back(model.dofmap.cell_nodes(c)[0]);
  assembly::StructuredNonlocalOperator K(assembly::offset_blocks(small.nonlocal_space(), centre),
                                         model.mesh.structure->cells, node_of_cell);
  return {std::move(model), std::move(K)};
}

std::vector<double> random_vector(Index n) {
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> x(static_cast<std::size_t>(n));
  for (double& v : x) v = u(gen);
  return x;
}

void expect_product_equals_assembly(int dim, std::array<Index, 3> cells) {
  const Fixture f = make(dim, cells);
  const Eigen::MatrixXd K = system::assemble_stiffness(f.model).K.to_dense();
  const std::vector<double> x = random_vector(static_cast<Index>(K.rows()));
  std::vector<double> y(x.size());
  f.K.apply(x, y);
  const Eigen::VectorXd ref = K * Eigen::Map<const Eigen::VectorXd>(x.data(), K.rows());
  const double err = (Eigen::Map<const Eigen::VectorXd>(y.data(), K.rows()) - ref).lpNorm<Eigen::Infinity>();
  std::printf("%dD, %zu offsets: |K x - assembled K x| = %.3e of %.3e\n", dim, f.K.offsets(), err,
              ref.lpNorm<Eigen::Infinity>());
  EXPECT_LT(err, 1e-13 * ref.lpNorm<Eigen::Infinity>());
  // Its own assembly equals the assembled stiffness, on a pattern with no zero block.
  testing::DenseInserter D(static_cast<Index>(K.rows()));
  f.K.assemble(D);
  EXPECT_LT((D.A - K).lpNorm<Eigen::Infinity>(), 1e-13 * K.lpNorm<Eigen::Infinity>());
  const assembly::SparsityPattern p = f.K.sparsity();
  for (Index r = 0; r < p.num_block_rows(); ++r)
    for (Index c : p.row(r))
      EXPECT_GT(D.A.block(r * dim, c * dim, dim, dim).lpNorm<Eigen::Infinity>(), 0.0) << r << ", " << c;
}

TEST(StructuredNonlocalOperator, ProductEqualsTheAssembledStiffness3D) {
  expect_product_equals_assembly(3, {6, 5, 4});
}

TEST(StructuredNonlocalOperator, ProductEqualsTheAssembledStiffness2D) {
  expect_product_equals_assembly(2, {9, 6, 1});
}

TEST(StructuredNonlocalOperator, FlaggedCellsGiveTheirRowsOfTheWholeAssemblyAndPattern) {
  const Fixture f = make(3, {6, 5, 4});
  const Index cells = 6 * 5 * 4, n = f.model.dofmap.num_dofs();
  std::vector<char> flagged(static_cast<std::size_t>(cells), 0);
  for (Index c = 0; c < cells; c += 3) flagged[static_cast<std::size_t>(c)] = 1;
  testing::DenseInserter whole(n), part(n);
  f.K.assemble(whole);
  f.K.assemble(part, flagged);
  const assembly::SparsityPattern all = f.K.sparsity(), mine = f.K.sparsity(flagged);
  ASSERT_EQ(mine.num_block_rows(), all.num_block_rows());
  std::vector<char> row_flagged(static_cast<std::size_t>(all.num_block_rows()), 0);
  for (Index c = 0; c < cells; ++c)
    if (flagged[static_cast<std::size_t>(c)])
      row_flagged[static_cast<std::size_t>(f.model.dofmap.cell_nodes(c)[0])] = 1;
  for (Index r = 0; r < all.num_block_rows(); ++r) {
    const bool in = row_flagged[static_cast<std::size_t>(r)] != 0;
    const auto a = all.row(r), m = mine.row(r);
    if (in)
      EXPECT_TRUE(std::equal(a.begin(), a.end(), m.begin(), m.end())) << "row " << r;
    else
      EXPECT_TRUE(m.empty()) << "row " << r;
    const int dim = 3;
    const Eigen::MatrixXd expected =
        in ? Eigen::MatrixXd(whole.A.middleRows(r * dim, dim)) : Eigen::MatrixXd::Zero(dim, n);
    EXPECT_TRUE((part.A.middleRows(r * dim, dim).array() == expected.array()).all()) << "row " << r;
  }
}

/// A window of the grid holding some cells (a process's piece, issue 17):
/// the product, pattern and assembly of its flagged cells are the whole
/// grid's rows, bit for bit, reading the window's cells only; a flagged cell
/// whose bond leaves the window or the piece is refused by nodes_read.
TEST(StructuredNonlocalOperator, OnAWindowGivesTheWholeGridsRowsBitForBit) {
  const Fixture f = make(3, {8, 7, 6});
  const std::array<Index, 3> n{8, 7, 6};
  // Flagged: the cells with i ≥ 5 (a part along x); the window: i ≥ 1, beyond their reach to the left.
  const assembly::GridWindow window{{1, 0, 0}, {7, 7, 6}};
  std::vector<Index> node_of_window;  // piece-local nodes: the window's cells in order
  std::vector<Index> whole_cell;      // the grid cell of each window cell
  std::vector<char> flagged;
  for (Index k = 0; k < 6; ++k)
    for (Index j = 0; j < 7; ++j)
      for (Index i = 1; i < 8; ++i) {
        whole_cell.push_back(i + n[0] * (j + n[1] * k));
        node_of_window.push_back(static_cast<Index>(node_of_window.size()));
        flagged.push_back(i >= 5 ? 1 : 0);
      }
  const std::vector<double> x_whole = random_vector(f.model.dofmap.num_dofs());
  std::vector<double> y_whole(x_whole.size());
  f.K.apply(x_whole, y_whole);
  const assembly::OffsetBlocks blocks = [&] {
    const auto small = setup::build_discretization(grid(3, {7, 7, 7}));
    return assembly::offset_blocks(small.nonlocal_space(), 3 + 7 * 3 + 49 * 3);
  }();
  const assembly::StructuredNonlocalOperator W(blocks, n, window, node_of_window);
  // x on the window only (the whole model's values there), y of the flagged rows.
  std::vector<double> x(node_of_window.size() * 3), y(x.size(), std::nan(""));
  for (std::size_t w = 0; w < whole_cell.size(); ++w)
    for (std::size_t d = 0; d < 3; ++d)
      x[3 * w + d] = x_whole[3 * static_cast<std::size_t>(f.model.dofmap.cell_nodes(whole_cell[w])[0]) + d];
  W.apply(x, y, flagged);
  for (std::size_t w = 0; w < whole_cell.size(); ++w) {
    if (!flagged[w]) continue;
    const auto node = static_cast<std::size_t>(f.model.dofmap.cell_nodes(whole_cell[w])[0]);
    for (std::size_t d = 0; d < 3; ++d) EXPECT_EQ(y[3 * w + d], y_whole[3 * node + d]) << "window cell " << w;
  }
  // It reads the whole grid's reach of the flagged cells, in window numbers.
  std::vector<char> flagged_whole(static_cast<std::size_t>(f.model.mesh.num_cells()), 0);
  for (std::size_t w = 0; w < whole_cell.size(); ++w)
    flagged_whole[static_cast<std::size_t>(whole_cell[w])] = flagged[w];
  std::vector<Index> reach;
  for (Index node : f.K.nodes_read(flagged_whole))
    for (std::size_t w = 0; w < whole_cell.size(); ++w)
      if (f.model.dofmap.cell_nodes(whole_cell[w])[0] == node) reach.push_back(static_cast<Index>(w));
  std::ranges::sort(reach);
  EXPECT_EQ(W.nodes_read(flagged), reach);
  // Pattern and assembly: the whole grid's rows, renumbered.
  testing::DenseInserter whole(f.model.dofmap.num_dofs()), mine(static_cast<Index>(x.size()));
  f.K.assemble(whole);
  W.assemble(mine, flagged);
  const assembly::SparsityPattern p = W.sparsity(flagged), all = f.K.sparsity();
  for (std::size_t w = 0; w < whole_cell.size(); ++w) {
    const auto row = p.row(static_cast<Index>(w));
    if (!flagged[w]) {
      EXPECT_TRUE(row.empty());
      continue;
    }
    const Index node = f.model.dofmap.cell_nodes(whole_cell[w])[0];
    std::vector<Index> expected;
    for (std::size_t v = 0; v < whole_cell.size(); ++v)
      if (std::ranges::find(all.row(node), f.model.dofmap.cell_nodes(whole_cell[v])[0]) !=
          all.row(node).end())
        expected.push_back(static_cast<Index>(v));
    EXPECT_TRUE(std::ranges::equal(row, expected)) << "window cell " << w;
    for (std::size_t v = 0; v < whole_cell.size(); ++v) {
      const Index col = f.model.dofmap.cell_nodes(whole_cell[v])[0];
      EXPECT_TRUE((mine.A.block(static_cast<Index>(3 * w), static_cast<Index>(3 * v), 3, 3).array() ==
                   whole.A.block(3 * node, 3 * col, 3, 3).array())
                      .all());
    }
  }
  // A flagged cell at i = 2 reaches i = 0 (the horizon is 2.01 cells): outside the window.
  std::vector<char> too_far(flagged.size(), 0);
  too_far[1] = 1;
  EXPECT_THROW((void)W.nodes_read(too_far), Error);
  // A cell of the window the piece does not hold (−1) is refused too.
  std::vector<Index> holed = node_of_window;
  holed[3] = -1;
  const assembly::StructuredNonlocalOperator H(blocks, n, window, holed);
  std::vector<char> next_to_hole(flagged.size(), 0);
  next_to_hole[4] = 1;
  EXPECT_THROW((void)H.nodes_read(next_to_hole), Error);
}

TEST(StructuredNonlocalOperator, SameForAnyThreadCount) {
  const Fixture f = make(3, {8, 7, 6});
  const std::vector<double> x = random_vector(f.model.dofmap.num_dofs());
  std::vector<double> y1(x.size()), y2(x.size());
  const int before = omp_get_max_threads();
  omp_set_num_threads(1);
  f.K.apply(x, y1);
  omp_set_num_threads(2);
  f.K.apply(x, y2);
  omp_set_num_threads(before);
  EXPECT_EQ(y1, y2);
}

TEST(StructuredNonlocalOperator, NeedsAStructuredOnePointPerCellSpace) {
  auto c = grid(3, {7, 7, 7});
  c.nonlocal.discretization = casefile::Discretization::discontinuous;
  c.nonlocal.quadrature = 2;
  const auto model = setup::build_discretization(c);
  EXPECT_THROW(assembly::offset_blocks(model.nonlocal_space(), 3 + 7 * 3 + 49 * 3), Error);
  const auto dg0 = setup::build_discretization(grid(3, {7, 7, 7}));
  EXPECT_THROW(assembly::offset_blocks(dg0.nonlocal_space(), 0), Error);  // a corner: offsets outside
}

}  // namespace
}  // namespace perimorph
