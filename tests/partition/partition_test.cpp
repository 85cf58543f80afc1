// Cells over ranks (partition/partition.hpp, la/graph_partition.hpp): the
// coordinate bisection is balanced, deterministic and cuts where the geometry
// says; the coupling graph is the node-sharing cells plus the cell graph; the
// halo equals a brute-force count; PT-Scotch gives a valid, balanced owner.

#include "perimorph/partition/partition.hpp"

#include "perimorph/bonds/cell_graph.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/la/graph_partition.hpp"
#include "perimorph/mesh/box.hpp"
#include "perimorph/mesh/mesh.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

namespace perimorph {
namespace {

mesh::Mesh box(int dim, std::array<Index, 3> cells, Vec3 upper) {
  mesh::BoxSpec spec;
  spec.dim = dim;
  spec.upper = upper;
  spec.cells = cells;
  return mesh::make_box(spec);
}

TEST(Partition, BisectionIsBalancedForAnyNumberOfParts) {
  const auto m = box(3, {7, 5, 3}, Vec3(7, 5, 3));
  for (int parts : {1, 2, 3, 5, 8, 13}) {
    const auto p = partition::coordinate_bisection(m, parts);
    std::vector<Index> size(static_cast<std::size_t>(parts), 0);
    for (int o : p.owner) {
      ASSERT_GE(o, 0);
      ASSERT_LT(o, parts);
      ++size[static_cast<std::size_t>(o)];
    }
    const auto [lo, hi] = std::minmax_element(size.begin(), size.end());
    EXPECT_LE(*hi - *lo, 4) << parts << " parts";  // at most one cell per bisection level
    EXPECT_EQ(partition::coordinate_bisection(m, parts).owner, p.owner) << "deterministic";
  }
}

TEST(Partition, BisectionCutsTheLongestExtentFirst) {
  const auto m = box(2, {8, 2, 1}, Vec3(8, 2, 0));  // long in x
  const auto p = partition::coordinate_bisection(m, 2);
  for (Index c = 0; c < m.num_cells(); ++c)
    EXPECT_EQ(p.owner[static_cast<std::size_t>(c)], m.cell_centroid(c).x() < 4.0 ? 0 : 1) << c;
  EXPECT_THROW(partition::coordinate_bisection(m, 0), Error);
  EXPECT_THROW(partition::coordinate_bisection(m, 17), Error);
}

TEST(Partition, CouplingGraphIsNodeSharingPlusTheCellGraph) {
  const auto m = box(2, {4, 3, 1}, Vec3(4, 3, 0));
  // Cell graph: cell 0 with the far corner cell 11 (as a long bond would).
  const std::vector<std::pair<Index, Index>> far{{0, 11}};
  const auto g = partition::coupling_graph(m, bonds::CellGraph::from_pairs(m.num_cells(), far));
  for (Index c = 0; c < m.num_cells(); ++c) {
    std::set<Index> expect{c};
    for (Index d = 0; d < m.num_cells(); ++d) {
      const auto a = m.cell(c), b = m.cell(d);
      for (Index v : a)
        if (std::find(b.begin(), b.end(), v) != b.end()) expect.insert(d);
    }
    if (c == 0) expect.insert(11);
    if (c == 11) expect.insert(0);
    const auto row = g.row(c);
    EXPECT_EQ(std::vector<Index>(row.begin(), row.end()), std::vector<Index>(expect.begin(), expect.end()))
        << c;
  }
}

TEST(Partition, HaloEqualsABruteForceCount) {
  const auto m = box(2, {6, 6, 1}, Vec3(6, 6, 0));
  const auto coupling = partition::coupling_graph(m, bonds::find_cell_neighbors(m, 1.5));
  const auto p = partition::coordinate_bisection(m, 4);
  const auto h = partition::halo(coupling, p);
  std::size_t pairs = 0, cut = 0;
  for (int q = 0; q < 4; ++q) {
    std::set<Index> ghosts;
    std::set<int> parts;
    for (Index c = 0; c < m.num_cells(); ++c)
      if (p.owner[static_cast<std::size_t>(c)] == q)
        for (Index d : coupling.row(c))
          if (p.owner[static_cast<std::size_t>(d)] != q) {
            ghosts.insert(d);
            parts.insert(p.owner[static_cast<std::size_t>(d)]);
          }
    EXPECT_EQ(h.owned[static_cast<std::size_t>(q)], 9);
    EXPECT_EQ(h.ghosts[static_cast<std::size_t>(q)], static_cast<Index>(ghosts.size())) << q;
    EXPECT_EQ(h.neighbours[static_cast<std::size_t>(q)], static_cast<int>(parts.size())) << q;
  }
  for (Index c = 0; c < m.num_cells(); ++c)
    for (Index d : coupling.row(c))
      if (c < d) {
        ++pairs;
        cut += p.owner[static_cast<std::size_t>(c)] != p.owner[static_cast<std::size_t>(d)];
      }
  EXPECT_EQ(h.pairs, pairs);
  EXPECT_EQ(h.cut_pairs, cut);
  EXPECT_GT(h.cut_pairs, 0u);
  // 3×3 quadrants, reach 1.5 cells (boxes closer than 1.5: up to one cell between, and the
  // diagonal cell at gap √2): each quadrant's halo is the 5×5 corner block less itself, 16 cells.
  for (Index g : h.ghosts) EXPECT_EQ(g, 16);
}

TEST(Partition, PtScotchGivesABalancedValidOwner) {
  const auto m = box(3, {8, 6, 4}, Vec3(8, 6, 4));
  const auto coupling = partition::coupling_graph(m, bonds::find_cell_neighbors(m, 1.0));
  const auto owner = la::partition_graph(coupling.offsets, coupling.neighbors, 4, "ptscotch");
  ASSERT_EQ(owner.size(), static_cast<std::size_t>(m.num_cells()));
  std::vector<int> size(4, 0);
  for (int o : owner) {
    ASSERT_GE(o, 0);
    ASSERT_LT(o, 4);
    ++size[static_cast<std::size_t>(o)];
  }
  for (int s : size) EXPECT_NEAR(s, 48, 48 * 0.1);  // PT-Scotch's default imbalance is a few %
  const auto h = partition::halo(coupling, partition::Partition{4, owner});
  EXPECT_GT(h.cut_pairs, 0u);
  EXPECT_THROW(la::partition_graph(coupling.offsets, coupling.neighbors, 4, "no-such-partitioner"),
               InputError);
}

}  // namespace
}  // namespace perimorph
