// Node-graph sparsity: row sizes on a structured grid, symmetry, sortedness,
// DG cells, extra (non-local) cell pairs.
#include "perimorph/assembly/sparsity.hpp"
#include "perimorph/bonds/cell_graph.hpp"
#include "perimorph/dofs/dof_map.hpp"
#include "perimorph/mesh/box.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <utility>
#include <vector>

namespace perimorph::assembly {
namespace {

mesh::Mesh box(int dim, std::array<Index, 3> cells) {
  mesh::BoxSpec s;
  s.dim = dim;
  s.upper = Vec3(static_cast<double>(cells[0]), static_cast<double>(cells[1]), static_cast<double>(cells[2]));
  s.cells = cells;
  return mesh::make_box(s);
}

/// Independent reference: row r = every dof node sharing a cell (or an extra
/// cell pair, either direction) with r.
std::vector<std::set<Index>> reference(const dofs::DofMap& dm,
                                       const std::vector<std::pair<Index, Index>>& pairs) {
  std::vector<std::set<Index>> rows(static_cast<std::size_t>(dm.num_nodes()));
  auto couple = [&](Index c, Index e) {
    for (Index a : dm.cell_nodes(c))
      for (Index b : dm.cell_nodes(e)) {
        rows[static_cast<std::size_t>(a)].insert(b);
        rows[static_cast<std::size_t>(b)].insert(a);
      }
  };
  for (Index c = 0; c < dm.num_cells(); ++c) couple(c, c);
  for (auto [c, e] : pairs) couple(c, e);
  return rows;
}

/// Structure every pattern must have, and equality with the reference.
void expect_valid(const SparsityPattern& p, const dofs::DofMap& dm,
                  const std::vector<std::pair<Index, Index>>& pairs) {
  ASSERT_EQ(p.num_block_rows(), dm.num_nodes());
  ASSERT_EQ(p.row_offsets.size(), static_cast<std::size_t>(dm.num_nodes()) + 1);
  EXPECT_EQ(p.row_offsets.front(), 0);
  EXPECT_EQ(p.row_offsets.back(), static_cast<Index>(p.columns.size()));
  EXPECT_EQ(p.block_size, dm.block_size());
  const auto ref = reference(dm, pairs);
  for (Index r = 0; r < p.num_block_rows(); ++r) {
    const auto row = p.row(r);
    EXPECT_TRUE(std::adjacent_find(row.begin(), row.end(), [](Index a, Index b) { return a >= b; }) ==
                row.end())
        << "row " << r << " not strictly ascending";
    EXPECT_TRUE(std::binary_search(row.begin(), row.end(), r)) << "row " << r << " lacks the diagonal";
    for (Index c : row) {
      ASSERT_GE(c, 0);
      ASSERT_LT(c, dm.num_nodes());
      const auto other = p.row(c);
      EXPECT_TRUE(std::binary_search(other.begin(), other.end(), r)) << "asymmetric " << r << "," << c;
    }
    EXPECT_EQ(
        std::vector<Index>(row.begin(), row.end()),
        std::vector<Index>(ref[static_cast<std::size_t>(r)].begin(), ref[static_cast<std::size_t>(r)].end()))
        << "row " << r;
  }
}

TEST(AssemblySparsity, StructuredQuadRowSizes) {
  const mesh::Mesh m = box(2, {3, 2, 1});  // 4 × 3 nodes, node (i, j) = i + 4 j
  const dofs::DofMap dm(m, 2);
  const SparsityPattern p = build_sparsity(dm);
  expect_valid(p, dm, {});
  ASSERT_EQ(p.num_block_rows(), 12);
  EXPECT_EQ(p.block_size, 2);
  for (Index j = 0; j < 3; ++j)
    for (Index i = 0; i < 4; ++i) {
      const bool edge_x = i == 0 || i == 3, edge_y = j == 0 || j == 2;
      const std::size_t expected = edge_x && edge_y ? 4u : (edge_x || edge_y ? 6u : 9u);
      EXPECT_EQ(p.row(i + 4 * j).size(), expected) << "node (" << i << ", " << j << ")";
    }
  EXPECT_EQ(std::vector<Index>(p.row(5).begin(), p.row(5).end()),
            (std::vector<Index>{0, 1, 2, 4, 5, 6, 8, 9, 10}));
  EXPECT_EQ(p.columns.size(), 4u * 4u + 6u * 6u + 2u * 9u);
}

TEST(AssemblySparsity, StructuredHexInteriorRow) {
  const mesh::Mesh m = box(3, {2, 2, 2});
  const dofs::DofMap dm(m, 3);
  const SparsityPattern p = build_sparsity(dm);
  expect_valid(p, dm, {});
  EXPECT_EQ(p.row(13).size(), 27u);  // the centre node
  EXPECT_EQ(p.row(0).size(), 8u);    // a corner
  EXPECT_EQ(p.row(1).size(), 12u);   // an edge midpoint
  EXPECT_EQ(p.row(4).size(), 18u);   // a face centre
}

TEST(AssemblySparsity, DiscontinuousCellsGetPrivateNodes) {
  const mesh::Mesh m = box(2, {3, 2, 1});
  // Cells (0,0) and (1,1) discontinuous; mesh node 0 is then touched by no CG cell.
  std::vector<dofs::Continuity> flags(6, dofs::Continuity::continuous);
  flags[0] = flags[4] = dofs::Continuity::discontinuous;
  const dofs::DofMap dm(m, 2, flags);
  // Independent count: mesh nodes touched by a CG cell, plus 4 per DG cell.
  std::set<Index> cg;
  for (Index c = 0; c < m.num_cells(); ++c)
    if (flags[static_cast<std::size_t>(c)] == dofs::Continuity::continuous)
      cg.insert(m.cell(c).begin(), m.cell(c).end());
  EXPECT_EQ(cg.size(), 11u);
  ASSERT_EQ(dm.num_nodes(), 11 + 2 * 4);
  EXPECT_EQ(dm.num_dofs(), 2 * 19);
  const SparsityPattern p = build_sparsity(dm);
  expect_valid(p, dm, {});
  for (Index c : {0, 4}) {
    std::vector<Index> own(dm.cell_nodes(c).begin(), dm.cell_nodes(c).end());
    std::sort(own.begin(), own.end());
    for (Index n : own) {
      EXPECT_GE(n, 11) << "DG node numbered among CG nodes";
      EXPECT_EQ(std::vector<Index>(p.row(n).begin(), p.row(n).end()), own)
          << "DG node " << n << " of cell " << c;
    }
  }
  // CG rows never reach DG nodes.
  for (Index r = 0; r < 11; ++r)
    for (Index col : p.row(r)) EXPECT_LT(col, 11) << "row " << r;
  // Mesh node 5 (interior): CG neighbours from cells 1 and 3 only → 7 entries.
  const Index cg5 = dm.cell_nodes(1)[2];
  EXPECT_EQ(dm.mesh_node(cg5), 5);
  EXPECT_EQ(p.row(cg5).size(), 7u);
  // Mesh node 5 has three dof nodes: its CG node and one copy in each DG cell.
  const std::vector<Index> five{5};
  EXPECT_EQ(dm.dof_nodes_of_mesh_nodes(five).size(), 3u);
}

TEST(AssemblySparsity, AllDiscontinuousIsBlockDiagonal) {
  const mesh::Mesh m = box(2, {2, 2, 1});
  const std::vector<dofs::Continuity> flags(4, dofs::Continuity::discontinuous);
  const dofs::DofMap dm(m, 2, flags);
  ASSERT_EQ(dm.num_nodes(), 16);
  const SparsityPattern p = build_sparsity(dm);
  expect_valid(p, dm, {});
  EXPECT_EQ(p.columns.size(), 16u * 4u);
}

TEST(AssemblySparsity, ExtraCellPairsWidenRows) {
  const mesh::Mesh m = box(2, {3, 2, 1});
  const dofs::DofMap dm(m, 2);
  const SparsityPattern base = build_sparsity(dm);
  const std::vector<std::pair<Index, Index>> pairs{{0, 5}};  // cells (0,0) and (2,1)
  const auto graph = bonds::CellGraph::from_pairs(m.num_cells(), pairs);
  const SparsityPattern p = build_sparsity(dm, &graph);
  expect_valid(p, dm, pairs);
  // Node 0 (only in cell 0) now couples to cell 5's nodes 6, 7, 10, 11.
  EXPECT_EQ(std::vector<Index>(p.row(0).begin(), p.row(0).end()),
            (std::vector<Index>{0, 1, 4, 5, 6, 7, 10, 11}));
  // Node 11 (only in cell 5) couples to cell 0's nodes.
  EXPECT_EQ(std::vector<Index>(p.row(11).begin(), p.row(11).end()),
            (std::vector<Index>{0, 1, 4, 5, 6, 7, 10, 11}));
  // Node 6 already had 9 entries; 0 and 4 are added (1 and 5 were there).
  EXPECT_EQ(p.row(6).size(), 11u);
  EXPECT_GT(p.columns.size(), base.columns.size());
  // Every base entry survives.
  for (Index r = 0; r < base.num_block_rows(); ++r)
    for (Index c : base.row(r)) EXPECT_TRUE(std::binary_search(p.row(r).begin(), p.row(r).end(), c));
  // A pair given in the other order, a duplicate, or a cell with itself yields the same pattern.
  const std::vector<std::pair<Index, Index>> same{{5, 0}, {0, 5}, {3, 3}};
  const auto same_graph = bonds::CellGraph::from_pairs(m.num_cells(), same);
  const SparsityPattern q = build_sparsity(dm, &same_graph);
  EXPECT_EQ(q.row_offsets, p.row_offsets);
  EXPECT_EQ(q.columns, p.columns);
}

TEST(AssemblySparsity, KeptRowsAreTheWholePatternsRowsAndTheOthersEmpty) {
  const mesh::Mesh m = box(2, {4, 3, 1});
  const dofs::DofMap dm(m, 2);
  const std::vector<std::pair<Index, Index>> pairs{{0, 5}, {2, 11}, {4, 9}};
  const auto graph = bonds::CellGraph::from_pairs(m.num_cells(), pairs);
  const SparsityPattern whole = build_sparsity(dm, &graph);
  const auto odd = [](Index r) { return r % 2 == 1; };
  const SparsityPattern part = build_sparsity(dm, &graph, odd);
  ASSERT_EQ(part.num_block_rows(), whole.num_block_rows());
  EXPECT_EQ(part.block_size, whole.block_size);
  std::size_t kept = 0;
  for (Index r = 0; r < whole.num_block_rows(); ++r) {
    const auto w = whole.row(r), q = part.row(r);
    if (odd(r)) {
      EXPECT_TRUE(std::equal(w.begin(), w.end(), q.begin(), q.end())) << "row " << r;
      kept += w.size();
    } else {
      EXPECT_TRUE(q.empty()) << "row " << r;
    }
  }
  EXPECT_EQ(part.columns.size(), kept);
  EXPECT_LT(part.columns.size(), whole.columns.size());
}

}  // namespace
}  // namespace perimorph::assembly
