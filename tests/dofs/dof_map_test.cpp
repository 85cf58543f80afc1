// The dof map's nodes and where they sit: CG nodes at the mesh's vertices, DG
// copies of their cell's vertices, a DG degree 0 node at its cell's centroid
// (THEORY §4), found from the mesh since the map keeps no coordinates.

#include "perimorph/dofs/dof_map.hpp"
#include "perimorph/mesh/box.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace perimorph {
namespace {

using dofs::Continuity;

TEST(DofMap, EachNodeSitsAtItsVertexOrCentroid) {
  // 3 × 2 quads on [0, 3] × [0, 1]: cell 1 DG, cell 4 DG degree 0, the rest CG.
  const mesh::Mesh m = mesh::make_box({2, Vec3::Zero(), Vec3(3.0, 1.0, 0.0), {3, 2, 1}});
  std::vector<Continuity> flags(6, Continuity::continuous);
  flags[1] = Continuity::discontinuous;
  flags[4] = Continuity::discontinuous_constant;
  const dofs::DofMap dm(m, 2, flags);
  ASSERT_EQ(dm.num_nodes(), 12 + 4 + 1);  // every vertex is a CG cell's; 4 DG copies; 1 centroid
  const std::vector<Vec3> all = dm.node_coordinates(m);
  ASSERT_EQ(static_cast<Index>(all.size()), dm.num_nodes());
  for (Index c = 0; c < m.num_cells(); ++c) {
    const auto nodes = dm.cell_nodes(c);
    if (c == 4) {
      ASSERT_EQ(nodes.size(), 1u);
      EXPECT_EQ(dm.mesh_node(nodes[0]), -1);
      EXPECT_EQ(dm.centroid_cell(nodes[0]), 4);
      EXPECT_EQ(dm.node_coordinate(m, nodes[0]), m.cell_centroid(4));
      EXPECT_EQ(dm.node_coordinate(m, nodes[0]), Vec3(1.5, 0.75, 0.0));
      continue;
    }
    ASSERT_EQ(nodes.size(), 4u);
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const Index vertex = m.cell(c)[i];
      EXPECT_EQ(dm.mesh_node(nodes[i]), vertex) << "cell " << c;
      EXPECT_EQ(dm.centroid_cell(nodes[i]), -1) << "cell " << c;
      EXPECT_EQ(dm.node_coordinate(m, nodes[i]), m.node(vertex)) << "cell " << c;
      EXPECT_EQ(all[static_cast<std::size_t>(nodes[i])], m.node(vertex)) << "cell " << c;
      EXPECT_EQ(nodes[i] >= 12, c == 1) << "cell " << c << ": DG nodes follow the CG ones";
    }
  }
  // The solver's view of the same coordinates.
  const auto at = dm.node_coordinate_on(m);
  for (Index n = 0; n < dm.num_nodes(); ++n) EXPECT_EQ(at(n), all[static_cast<std::size_t>(n)]) << n;
}

TEST(DofMap, CentroidNodesOfEveryCell) {
  // All DG degree 0 (the meshfree discretization): one node per cell, at its
  // centroid, numbered in cell order; no mesh node has a copy.
  const mesh::Mesh m = mesh::make_box({3, Vec3::Zero(), Vec3(2.0, 1.0, 1.0), {2, 1, 1}});
  const std::vector<Continuity> flags(2, Continuity::discontinuous_constant);
  const dofs::DofMap dm(m, 3, flags);
  ASSERT_EQ(dm.num_nodes(), 2);
  EXPECT_EQ(dm.centroid_cell(0), 0);
  EXPECT_EQ(dm.centroid_cell(1), 1);
  EXPECT_EQ(dm.node_coordinate(m, 1), Vec3(1.5, 0.5, 0.5));
  const std::vector<Index> every_vertex{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11};
  EXPECT_TRUE(dm.dof_nodes_of_mesh_nodes(every_vertex).empty());
}

}  // namespace
}  // namespace perimorph
