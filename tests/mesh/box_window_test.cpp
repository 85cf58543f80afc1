// A window of a box mesh built from the grid alone (mesh/box_window.hpp) is
// the piece part_mesh cuts from the whole box, array for array and bit for bit.

#include "perimorph/mesh/box_window.hpp"

#include "perimorph/core/error.hpp"

#include <gtest/gtest.h>

namespace perimorph {
namespace {

void expect_same(const mesh::PartMesh& a, const mesh::PartMesh& b) {
  EXPECT_EQ(a.global_cell, b.global_cell);
  EXPECT_EQ(a.global_node, b.global_node);
  ASSERT_EQ(a.mesh.dim(), b.mesh.dim());
  EXPECT_EQ(a.mesh.nodes(), b.mesh.nodes());  // bit for bit
  EXPECT_EQ(a.mesh.connectivity(), b.mesh.connectivity());
  EXPECT_EQ(a.mesh.cell_region, b.mesh.cell_region);
  EXPECT_EQ(a.mesh.node_sets, b.mesh.node_sets);
  ASSERT_EQ(a.mesh.face_sets.size(), b.mesh.face_sets.size());
  for (const auto& [name, set] : a.mesh.face_sets) {
    const auto& other = b.mesh.face_sets.at(name);
    ASSERT_EQ(set.size(), other.size()) << name;
    for (std::size_t k = 0; k < set.size(); ++k) {
      EXPECT_EQ(set[k].cell, other[k].cell) << name;
      EXPECT_EQ(set[k].face, other[k].face) << name;
    }
  }
  EXPECT_EQ(a.mesh.cell_sets, b.mesh.cell_sets);
  ASSERT_TRUE(a.mesh.structure && b.mesh.structure);
  const auto &sa = *a.mesh.structure, &sb = *b.mesh.structure;
  EXPECT_EQ(sa.cells, sb.cells);
  EXPECT_EQ(sa.origin, sb.origin);
  EXPECT_EQ(sa.spacing, sb.spacing);
  EXPECT_EQ(sa.upper, sb.upper);
  EXPECT_EQ(sa.box_cells, sb.box_cells);
  EXPECT_TRUE(a.mesh.cuts.empty() && b.mesh.cuts.empty());
}

TEST(BoxWindow, IsThePiecePartMeshCutsFromTheWholeBox) {
  struct Case {
    mesh::BoxSpec spec;
    std::array<Index, 3> lo, hi;
  };
  const Case cases[] = {
      {{1, Vec3(0, 0, 0), Vec3(1.3, 0, 0), {9, 1, 1}}, {2, 0, 0}, {7, 1, 1}},
      {{2, Vec3(-1, 0.5, 0), Vec3(2.1, 3.3, 0), {7, 5, 1}}, {0, 1, 0}, {4, 5, 1}},  // touches xmin, ymax
      {{2, Vec3(0, 0, 0), Vec3(7, 5, 0), {7, 5, 1}}, {0, 0, 0}, {7, 5, 1}},         // the whole box
      {{3, Vec3(0, 0, 0), Vec3(1, 1, 1), {6, 5, 4}}, {1, 1, 1}, {5, 4, 3}},         // inside: no boundary
      {{3, Vec3(0.1, 0, -2), Vec3(3, 2, 0.7), {6, 5, 4}}, {3, 0, 2}, {6, 2, 4}},    // a corner
  };
  for (const Case& c : cases) {
    const mesh::PartMesh window = mesh::make_box_window(c.spec, c.lo, c.hi);
    const std::vector<Index> cells = mesh::box_window_cells(c.spec, c.lo, c.hi);
    EXPECT_EQ(cells, window.global_cell);
    expect_same(window, mesh::part_mesh(mesh::make_box(c.spec), cells));
  }
}

TEST(BoxWindow, RefusesARangeOutsideTheBox) {
  const mesh::BoxSpec spec{2, Vec3::Zero(), Vec3::Ones(), {4, 4, 1}};
  EXPECT_THROW(mesh::make_box_window(spec, {0, 0, 0}, {5, 4, 1}), Error);
  EXPECT_THROW(mesh::make_box_window(spec, {2, 0, 0}, {2, 4, 1}), Error);
  EXPECT_THROW(mesh::make_box_window(spec, {-1, 0, 0}, {2, 4, 1}), Error);
}

}  // namespace
}  // namespace perimorph
