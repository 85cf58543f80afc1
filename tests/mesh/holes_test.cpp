// Holes in the box mesh: the cells whose centroid lies in a shape are removed,
// unused nodes dropped, everything renumbered and the sets remapped.
#include "perimorph/mesh/holes.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/mesh/box.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>
#include <vector>

namespace perimorph::mesh {
namespace {

Mesh box(int dim, Vec3 upper, std::array<Index, 3> cells) {
  BoxSpec s;
  s.dim = dim;
  s.lower = Vec3::Zero();
  s.upper = upper;
  s.cells = cells;
  return make_box(s);
}

Hole disk(Vec3 center, double radius) {
  Hole h;
  h.dim = 2;
  h.shape = HoleShape::disk;
  h.center = center;
  h.radius = radius;
  return h;
}

/// Every node is used by some cell.
void expect_no_orphans(const Mesh& m) {
  std::vector<char> used(static_cast<std::size_t>(m.num_nodes()), 0);
  for (Index c = 0; c < m.num_cells(); ++c)
    for (Index n : m.cell(c)) used[static_cast<std::size_t>(n)] = 1;
  for (Index n = 0; n < m.num_nodes(); ++n)
    EXPECT_TRUE(used[static_cast<std::size_t>(n)]) << "orphan node " << n;
}

/// The centroids of all cells, rounded to a grid of 1e-9, for set comparisons.
std::set<std::pair<long long, long long>> centroids(const Mesh& m) {
  std::set<std::pair<long long, long long>> out;
  for (Index c = 0; c < m.num_cells(); ++c) {
    const Vec3 x = m.cell_centroid(c);
    out.insert({std::llround(x.x() * 1e9), std::llround(x.y() * 1e9)});
  }
  return out;
}

TEST(MeshHoles, DiskInTenByTenGrid) {
  // Centroids (i + 1/2, j + 1/2); radius 3 around (5, 5) takes the 6 x 6 block
  // of cells 2..7 less its four corners (distance sqrt(12.5) > 3): 32 cells.
  // The nodes gone are the 5 x 5 inside that block less the four next to the
  // kept corner cells: 21.
  Mesh m = box(2, Vec3(10, 10, 0), {10, 10, 1});
  ASSERT_TRUE(m.structure.has_value());
  EXPECT_EQ(remove_hole(m, disk(Vec3(5, 5, 0), 3.0)), 32);
  EXPECT_EQ(m.num_cells(), 100 - 32);
  EXPECT_EQ(m.num_nodes(), 121 - 21);
  EXPECT_FALSE(m.structure.has_value());
  expect_no_orphans(m);
  for (Index c = 0; c < m.num_cells(); ++c) EXPECT_GE((m.cell_centroid(c) - Vec3(5, 5, 0)).norm(), 3.0);
  // Nodes keep their order: the coordinates stay sorted by (y, x).
  for (Index n = 1; n < m.num_nodes(); ++n) {
    const Vec3 &a = m.node(n - 1), &b = m.node(n);
    EXPECT_TRUE(a.y() < b.y() || (a.y() == b.y() && a.x() < b.x())) << "node " << n;
  }
  // The outer boundary is untouched; "all" is every remaining cell.
  for (const char* side : {"xmin", "xmax", "ymin", "ymax"})
    EXPECT_EQ(m.node_sets.at(side).size(), 11u) << side;
  EXPECT_EQ(m.node_sets.at("boundary").size(), 40u);
  EXPECT_EQ(m.cell_sets.at("all").size(), 68u);
  EXPECT_EQ(m.cell_region.size(), 68u);
}

TEST(MeshHoles, CentredDiskOnEvenGridIsSymmetric) {
  const Vec3 upper(4, 2, 0);
  Mesh m = box(2, upper, {20, 10, 1});
  const Hole h = disk(0.5 * upper, 0.73);
  remove_hole(m, h);
  const auto kept = centroids(m);
  const auto key = [](double x, double y) {
    return std::make_pair(std::llround(x * 1e9), std::llround(y * 1e9));
  };
  Index removed = 0;
  for (Index i = 0; i < 20; ++i)
    for (Index j = 0; j < 10; ++j) {
      const double x = 0.2 * (i + 0.5), y = 0.2 * (j + 0.5);
      const bool in = !kept.count(key(x, y));
      removed += in ? 1 : 0;
      // Mirrors about x = 2 and y = 1 (cells 19 - i and 9 - j).
      EXPECT_EQ(in, !kept.count(key(0.2 * (19 - i + 0.5), y))) << i << ", " << j;
      EXPECT_EQ(in, !kept.count(key(x, 0.2 * (9 - j + 0.5)))) << i << ", " << j;
      EXPECT_EQ(in, h.contains(Vec3(x, y, 0))) << i << ", " << j;
    }
  EXPECT_GT(removed, 0);
  EXPECT_EQ(removed % 4, 0);  // four mirror images of every removed cell
  EXPECT_EQ(m.num_cells(), 200 - removed);
}

TEST(MeshHoles, SetsAndRegionsAreRemapped) {
  // A 2 x 2 block of cells at the corner (0, 0) of a 10 x 10 grid: its four
  // nodes with x, y < 2 go.
  Mesh m = box(2, Vec3(10, 10, 0), {10, 10, 1});
  for (Index c = 0; c < m.num_cells(); ++c) m.cell_region[static_cast<std::size_t>(c)] = c;  // old index
  const std::vector<Vec3> before = m.nodes();
  Hole h;
  h.dim = 2;
  h.shape = HoleShape::box;
  h.lower = Vec3(-1, -1, 0);
  h.upper = Vec3(2, 2, 0);
  EXPECT_EQ(remove_hole(m, h), 4);
  EXPECT_EQ(m.num_cells(), 96);
  EXPECT_EQ(m.num_nodes(), 117);
  expect_no_orphans(m);

  const auto& xmin = m.node_sets.at("xmin");
  ASSERT_EQ(xmin.size(), 9u);
  for (Index n : xmin) EXPECT_EQ(m.node(n).x(), 0.0);
  EXPECT_EQ(m.node(xmin.front()).y(), 2.0);
  EXPECT_TRUE(std::is_sorted(xmin.begin(), xmin.end()));
  const auto& ymin = m.node_sets.at("ymin");
  ASSERT_EQ(ymin.size(), 9u);
  for (Index n : ymin) EXPECT_EQ(m.node(n).y(), 0.0);
  EXPECT_EQ(m.node_sets.at("xmax").size(), 11u);
  EXPECT_EQ(m.node_sets.at("boundary").size(), 40u - 3u);  // (0,0), (1,0), (0,1)
  for (Index n : m.node_sets.at("boundary")) EXPECT_GE(m.node(n).x() + m.node(n).y(), 2.0);

  // Face sets: the two faces of the removed cells on xmin go, the rest follow their cells.
  const auto& xmin_faces = m.face_sets.at("xmin");
  ASSERT_EQ(xmin_faces.size(), 8u);
  for (const CellFace& f : xmin_faces) {
    EXPECT_EQ(f.face, 0);
    EXPECT_NEAR(m.cell_centroid(f.cell).x(), 0.5, 1e-12);
  }
  EXPECT_EQ(m.face_sets.at("boundary").size(), 40u - 4u);
  EXPECT_EQ(m.cell_sets.at("all").size(), 96u);
  for (Index c = 0; c < m.num_cells(); ++c) EXPECT_EQ(m.cell_sets.at("all")[static_cast<std::size_t>(c)], c);

  // Every remaining cell is the old cell region[c] (its old index), in order,
  // with the same node coordinates.
  const Mesh old = box(2, Vec3(10, 10, 0), {10, 10, 1});
  for (Index c = 0; c < m.num_cells(); ++c) {
    const Index was = m.cell_region[static_cast<std::size_t>(c)];
    if (c > 0) {
      EXPECT_GT(was, m.cell_region[static_cast<std::size_t>(c - 1)]);
    }
    for (int a = 0; a < m.nodes_per_cell(); ++a)
      EXPECT_EQ(m.node(m.cell(c)[static_cast<std::size_t>(a)]),
                before[static_cast<std::size_t>(old.cell(was)[static_cast<std::size_t>(a)])]);
  }
}

TEST(MeshHoles, CylinderAndBallIn3D) {
  // Cylinder along z through the centre of a 4 x 4 x 2 box: the central 2 x 2
  // columns (centroids at distance sqrt(1/2) < 0.8), 8 cells.
  Mesh m = box(3, Vec3(4, 4, 2), {4, 4, 2});
  Hole cyl;
  cyl.dim = 3;
  cyl.shape = HoleShape::cylinder;
  cyl.center = Vec3(2, 2, 100);  // z does not matter
  cyl.radius = 0.8;
  EXPECT_EQ(remove_hole(m, cyl), 8);
  EXPECT_EQ(m.num_cells(), 24);
  EXPECT_EQ(m.num_nodes(), 75 - 3);  // the central vertical line of nodes
  expect_no_orphans(m);

  Mesh b = box(3, Vec3(4, 4, 4), {4, 4, 4});
  Hole ball;
  ball.dim = 3;
  ball.shape = HoleShape::ball;
  ball.center = Vec3(2, 2, 2);
  ball.radius = 0.9;  // the 8 cells around the centre (distance sqrt(3)/2)
  EXPECT_EQ(remove_hole(b, ball), 8);
  EXPECT_EQ(b.num_nodes(), 125 - 1);
  expect_no_orphans(b);
}

TEST(MeshHoles, RemovingNothingOrEverythingIsAnInputError) {
  Mesh m = box(2, Vec3(10, 10, 0), {10, 10, 1});
  try {
    remove_hole(m, disk(Vec3(20, 20, 0), 1.0));
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("disk of radius 1 centred at [20, 20]"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("no cell centroid"), std::string::npos) << e.what();
  }
  try {
    remove_hole(m, disk(Vec3(5, 5, 0), 100.0));
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("every cell (100)"), std::string::npos) << e.what();
  }
  EXPECT_EQ(m.num_cells(), 100);  // unchanged
  EXPECT_TRUE(m.structure.has_value());
}

TEST(MeshHoles, RemoveCellsKeepsCutsAndAllowsEmptySets) {
  Mesh m = box(1, Vec3(4, 0, 0), {4, 1, 1});
  Cut cut;
  cut.dim = 1;
  cut.origin = Vec3(2, 0, 0);
  m.cuts.push_back(cut);
  remove_cells(m, {1, 0, 0, 0});
  EXPECT_EQ(m.num_cells(), 3);
  EXPECT_EQ(m.num_nodes(), 4);
  EXPECT_TRUE(m.node_sets.at("xmin").empty());
  EXPECT_EQ(m.node_sets.at("xmax"), std::vector<Index>{3});
  EXPECT_EQ(m.node(0).x(), 1.0);
  ASSERT_EQ(m.cuts.size(), 1u);
  EXPECT_EQ(m.cuts[0].origin, Vec3(2, 0, 0));
}

}  // namespace
}  // namespace perimorph::mesh
