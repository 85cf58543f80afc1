// A process's piece of the mesh (mesh/part_mesh.hpp): local numbers in the
// global order, every cell's nodes the whole mesh's, the sets cut to the
// piece under their own names.

#include "perimorph/mesh/part_mesh.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/mesh/box.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace perimorph {
namespace {

mesh::Mesh plate() {
  return mesh::make_box({2, Vec3(0, 0, 0), Vec3(6, 4, 0), {6, 4, 1}});
}

TEST(PartMesh, CellsAndNodesAreTheWholeMeshsInTheGlobalOrder) {
  const auto whole = plate();
  const std::vector<Index> cells{17, 3, 4, 9, 10};  // any order
  const auto piece = mesh::part_mesh(whole, cells);
  EXPECT_EQ(piece.global_cell, (std::vector<Index>{3, 4, 9, 10, 17}));
  ASSERT_EQ(piece.mesh.num_cells(), 5);
  EXPECT_TRUE(std::is_sorted(piece.global_node.begin(), piece.global_node.end()));
  ASSERT_EQ(piece.mesh.num_nodes(), static_cast<Index>(piece.global_node.size()));
  for (Index c = 0; c < piece.mesh.num_cells(); ++c) {
    const Index g = piece.global_cell[static_cast<std::size_t>(c)];
    EXPECT_EQ(piece.local_cell(g), c);
    const auto mine = piece.mesh.cell(c), theirs = whole.cell(g);
    for (std::size_t a = 0; a < mine.size(); ++a) {
      EXPECT_EQ(piece.global_node[static_cast<std::size_t>(mine[a])], theirs[a]);
      EXPECT_EQ(piece.mesh.node(mine[a]), whole.node(theirs[a]));
    }
  }
  // Every node used, and none other: 4 cells' worth less the shared ones.
  std::vector<Index> used;
  for (Index g : cells)
    for (Index n : whole.cell(g)) used.push_back(n);
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  EXPECT_EQ(piece.global_node, used);
  EXPECT_EQ(piece.local_cell(0), -1);
  EXPECT_EQ(piece.local_node(whole.num_nodes() - 1), -1);
}

TEST(PartMesh, SetsKeepTheirNamesAndThePiecesMembers) {
  auto whole = plate();
  whole.cell_region.assign(static_cast<std::size_t>(whole.num_cells()), 0);
  whole.cell_region[7] = 7;
  const std::vector<Index> cells{0, 1, 7};  // two on ymin (a row is 6 cells), none on ymax
  const auto piece = mesh::part_mesh(whole, cells);
  EXPECT_EQ(piece.mesh.set_names(), whole.set_names());
  EXPECT_TRUE(piece.mesh.node_sets.at("ymax").empty());
  EXPECT_TRUE(piece.mesh.face_sets.at("ymax").empty());
  ASSERT_TRUE(whole.structure.has_value());
  ASSERT_TRUE(piece.mesh.structure.has_value());
  // The layout is kept, each local cell its box cell's (i, j, k).
  EXPECT_EQ(piece.mesh.structure->box_cells, cells);
  for (Index l = 0; l < piece.mesh.num_cells(); ++l)
    EXPECT_EQ(piece.mesh.structure->cell_ijk(l),
              whole.structure->cell_ijk(piece.global_cell[static_cast<std::size_t>(l)]));
  // A piece of a piece keeps the box's numbers.
  const std::vector<Index> local{0, 2};
  const auto inner = mesh::part_mesh(piece.mesh, local);
  EXPECT_EQ(inner.mesh.structure->box_cells, (std::vector<Index>{0, 7}));
  for (const auto& [name, set] : whole.node_sets) {
    std::vector<Index> expected;
    for (Index n : set)
      if (piece.local_node(n) >= 0) expected.push_back(n);
    std::vector<Index> got;
    for (Index l : piece.mesh.node_sets.at(name))
      got.push_back(piece.global_node[static_cast<std::size_t>(l)]);
    EXPECT_EQ(got, expected) << name;
  }
  for (const auto& [name, set] : whole.face_sets) {
    std::vector<mesh::CellFace> expected;
    for (const auto& f : set)
      if (piece.local_cell(f.cell) >= 0) expected.push_back(f);
    std::vector<mesh::CellFace> got;
    for (const auto& f : piece.mesh.face_sets.at(name))
      got.push_back({piece.global_cell[static_cast<std::size_t>(f.cell)], f.face});
    EXPECT_EQ(got, expected) << name;
  }
  EXPECT_EQ(piece.mesh.face_sets.at("ymin").size(), 2u);  // cells 0 and 1
  EXPECT_EQ(piece.mesh.cell_sets.at("all").size(), 3u);
  EXPECT_EQ(piece.mesh.cell_region, (std::vector<int>{0, 0, 7}));
}

TEST(PartMesh, RefusesACellOutOfRangeOrListedTwice) {
  const auto whole = plate();
  EXPECT_THROW(mesh::part_mesh(whole, std::vector<Index>{0, 24}), Error);
  EXPECT_THROW(mesh::part_mesh(whole, std::vector<Index>{-1}), Error);
  EXPECT_THROW(mesh::part_mesh(whole, std::vector<Index>{5, 2, 5}), Error);
}

}  // namespace
}  // namespace perimorph
