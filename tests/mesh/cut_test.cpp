// Pre-crack splitting along element faces and the cut's geometry queries.
#include "perimorph/mesh/cut.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/mesh/box.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
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

Cut cut2(Vec3 origin, Vec3 edge1) {
  Cut c;
  c.dim = 2;
  c.origin = origin;
  c.edge1 = edge1;
  return c;
}

Cut cut3(Vec3 origin, Vec3 edge1, Vec3 edge2) {
  Cut c;
  c.dim = 3;
  c.origin = origin;
  c.edge1 = edge1;
  c.edge2 = edge2;
  return c;
}

std::set<Index> nodes_of(const Mesh& m, Index c) {
  return {m.cell(c).begin(), m.cell(c).end()};
}

std::set<Index> shared(const Mesh& m, Index a, Index b) {
  std::set<Index> out;
  const auto na = nodes_of(m, a), nb = nodes_of(m, b);
  std::set_intersection(na.begin(), na.end(), nb.begin(), nb.end(), std::inserter(out, out.begin()));
  return out;
}

/// Every node is used by some cell and every cell's nodes are distinct.
void expect_consistent(const Mesh& m) {
  std::vector<char> used(static_cast<std::size_t>(m.num_nodes()), 0);
  for (Index c = 0; c < m.num_cells(); ++c) {
    EXPECT_EQ(nodes_of(m, c).size(), static_cast<std::size_t>(m.nodes_per_cell())) << "cell " << c;
    for (Index n : m.cell(c)) used[static_cast<std::size_t>(n)] = 1;
  }
  for (Index n = 0; n < m.num_nodes(); ++n)
    EXPECT_TRUE(used[static_cast<std::size_t>(n)]) << "orphan node " << n;
}

// 4×4 quads on [0,4]²: node (i, j) = i + 5 j, cell (i, j) = i + 4 j.
TEST(MeshCut, EdgeCut2D) {
  Mesh m = box(2, Vec3(4, 4, 0), {4, 4, 1});
  const Cut cut = cut2(Vec3(0, 2, 0), Vec3(2, 0, 0));
  const CutReport r = split_along_cut(m, cut);
  EXPECT_EQ(r.faces_cut, 2);
  EXPECT_EQ(r.nodes_split, 2);
  ASSERT_EQ(m.num_nodes(), 25 + 2);
  EXPECT_EQ(m.num_cells(), 16);
  // The copies sit exactly at (0,2) and (1,2).
  std::vector<Vec3> copies{m.node(25), m.node(26)};
  std::sort(copies.begin(), copies.end(), [](const Vec3& a, const Vec3& b) { return a.x() < b.x(); });
  EXPECT_EQ(copies[0], Vec3(0, 2, 0));
  EXPECT_EQ(copies[1], Vec3(1, 2, 0));
  // Below (cells 4, 5) and above (cells 8, 9) the cut no longer share nodes 10, 11.
  EXPECT_TRUE(shared(m, 4, 8).empty());
  EXPECT_EQ(shared(m, 5, 9), std::set<Index>{12});  // only the tip
  // The tip x = 2 is not split: cells 6 and 10 still share nodes 12 and 13.
  EXPECT_EQ(shared(m, 6, 10), (std::set<Index>{12, 13}));
  // Each side stays connected along the cut: 4–5 share 11 (or its copy), 8–9 too.
  EXPECT_EQ(shared(m, 4, 5).size(), 2u);
  EXPECT_EQ(shared(m, 8, 9).size(), 2u);
  // Every cell's node coordinates are unchanged (a copy has its original's position).
  const Mesh fresh = box(2, Vec3(4, 4, 0), {4, 4, 1});
  for (Index c = 0; c < m.num_cells(); ++c)
    for (std::size_t a = 0; a < 4; ++a) EXPECT_EQ(m.node(m.cell(c)[a]), fresh.node(fresh.cell(c)[a]));
  expect_consistent(m);
  // Node sets gain the copies: (0,2) is on xmin and boundary; (1,2) is interior.
  EXPECT_EQ(m.node_sets.at("xmin").size(), 5u + 1u);
  EXPECT_EQ(m.node_sets.at("boundary").size(), 16u + 1u);
  EXPECT_EQ(m.node_sets.at("xmax").size(), 5u);
  EXPECT_TRUE(std::is_sorted(m.node_sets.at("xmin").begin(), m.node_sets.at("xmin").end()));
  for (Index n : m.node_sets.at("xmin")) EXPECT_EQ(m.node(n).x(), 0.0);
  // The cut is kept as geometry.
  ASSERT_EQ(m.cuts.size(), 1u);
  EXPECT_EQ(m.cuts[0].dim, 2);
  EXPECT_EQ(m.cuts[0].origin, cut.origin);
  EXPECT_EQ(m.cuts[0].edge1, cut.edge1);
}

TEST(MeshCut, ThroughCut2D) {
  Mesh m = box(2, Vec3(4, 4, 0), {4, 4, 1});
  const CutReport r = split_along_cut(m, cut2(Vec3(0, 2, 0), Vec3(4, 0, 0)));
  EXPECT_EQ(r.faces_cut, 4);
  EXPECT_EQ(r.nodes_split, 5);
  EXPECT_EQ(m.num_nodes(), 30);
  // The two halves are disconnected.
  for (Index a = 0; a < m.num_cells(); ++a)
    for (Index b = 0; b < m.num_cells(); ++b)
      if (m.cell_centroid(a).y() < 2 && m.cell_centroid(b).y() > 2) {
        EXPECT_TRUE(shared(m, a, b).empty()) << a << " " << b;
      }
  for (Index n = 25; n < 30; ++n) EXPECT_EQ(m.node(n).y(), 2.0);
  EXPECT_EQ(m.node_sets.at("xmin").size(), 6u);
  EXPECT_EQ(m.node_sets.at("xmax").size(), 6u);
  EXPECT_EQ(m.node_sets.at("boundary").size(), 18u);
  EXPECT_EQ(m.node_sets.at("ymin").size(), 5u);
  expect_consistent(m);
}

TEST(MeshCut, InteriorCrackStaysClosedAtBothFronts) {
  Mesh m = box(2, Vec3(4, 4, 0), {4, 4, 1});
  const CutReport r = split_along_cut(m, cut2(Vec3(1, 2, 0), Vec3(2, 0, 0)));
  EXPECT_EQ(r.faces_cut, 2);
  EXPECT_EQ(r.nodes_split, 1);  // only the middle node (2,2)
  ASSERT_EQ(m.num_nodes(), 26);
  EXPECT_EQ(m.node(25), Vec3(2, 2, 0));
  EXPECT_EQ(shared(m, 4, 8), (std::set<Index>{10, 11}));  // left of the crack: intact
  EXPECT_EQ(shared(m, 5, 9), std::set<Index>{11});        // front at x = 1
  EXPECT_EQ(shared(m, 6, 10), std::set<Index>{13});       // front at x = 3
  EXPECT_EQ(m.node_sets.at("boundary").size(), 16u);
}

TEST(MeshCut, PartialCut3D) {
  Mesh m = box(3, Vec3(4, 4, 4), {4, 4, 4});
  const CutReport r = split_along_cut(m, cut3(Vec3(0, 0, 2), Vec3(2, 0, 0), Vec3(0, 4, 0)));
  EXPECT_EQ(r.faces_cut, 2 * 4);
  EXPECT_EQ(r.nodes_split, 2 * 5);  // x in {0, 1}, y in 0..4, z = 2
  ASSERT_EQ(m.num_nodes(), 125 + 10);
  for (Index n = 125; n < m.num_nodes(); ++n) {
    EXPECT_EQ(m.node(n).z(), 2.0);
    EXPECT_TRUE(m.node(n).x() == 0.0 || m.node(n).x() == 1.0) << m.node(n).transpose();
  }
  // Cells across the cut for x < 2 share nothing; for x > 2 they share a face.
  auto cell = [](Index i, Index j, Index k) { return i + 4 * (j + 4 * k); };
  for (Index j = 0; j < 4; ++j) {
    EXPECT_TRUE(shared(m, cell(0, j, 1), cell(0, j, 2)).empty());
    EXPECT_EQ(shared(m, cell(1, j, 1), cell(1, j, 2)).size(), 2u);  // the front edge x = 2
    EXPECT_EQ(shared(m, cell(2, j, 1), cell(2, j, 2)).size(), 4u);
  }
  expect_consistent(m);
  // Copies of xmin nodes on the cut: 5 of them.
  EXPECT_EQ(m.node_sets.at("xmin").size(), 25u + 5u);
  EXPECT_EQ(m.node_sets.at("xmax").size(), 25u);
}

TEST(MeshCut, CutOffElementFacesThrows) {
  Mesh m = box(2, Vec3(4, 4, 0), {4, 4, 1});
  EXPECT_THROW(split_along_cut(m, cut2(Vec3(0, 2.5, 0), Vec3(4, 0, 0))), InputError);
  EXPECT_THROW(split_along_cut(m, cut2(Vec3(0, 0, 0), Vec3(4, 4, 0))), InputError);  // diagonal
  // On a boundary line only: no interior face is cut.
  EXPECT_THROW(split_along_cut(m, cut2(Vec3(0, 0, 0), Vec3(4, 0, 0))), InputError);
  EXPECT_EQ(m.num_nodes(), 25);
  EXPECT_TRUE(m.cuts.empty());
  Mesh h = box(3, Vec3(4, 4, 4), {4, 4, 4});
  EXPECT_THROW(split_along_cut(h, cut3(Vec3(0, 0, 2.5), Vec3(2, 0, 0), Vec3(0, 4, 0))), InputError);
  // Shorter than one face: no face has all its nodes on the cut.
  EXPECT_THROW(split_along_cut(h, cut3(Vec3(0, 0, 2), Vec3(0.5, 0, 0), Vec3(0, 4, 0))), InputError);
}

TEST(MeshCut, Bar1D) {
  Mesh m = box(1, Vec3(4, 0, 0), {4, 1, 1});
  Cut cut;
  cut.dim = 1;
  cut.origin = Vec3(2, 0, 0);
  const CutReport r = split_along_cut(m, cut);
  EXPECT_EQ(r.faces_cut, 1);
  EXPECT_EQ(r.nodes_split, 1);
  ASSERT_EQ(m.num_nodes(), 6);
  EXPECT_EQ(m.node(5), Vec3(2, 0, 0));
  EXPECT_TRUE(shared(m, 1, 2).empty());
  EXPECT_EQ(shared(m, 0, 1), std::set<Index>{1});
  EXPECT_EQ(m.node_sets.at("boundary").size(), 2u);
  ASSERT_EQ(m.cuts.size(), 1u);
  EXPECT_EQ(m.cuts[0].origin, Vec3(2, 0, 0));
  Mesh off = box(1, Vec3(4, 0, 0), {4, 1, 1});
  cut.origin = Vec3(2.5, 0, 0);
  EXPECT_THROW(split_along_cut(off, cut), InputError);
}

TEST(MeshCut, Crosses2D) {
  const Cut c = cut2(Vec3(0, 2, 0), Vec3(2, 0, 0));
  EXPECT_NEAR((c.normal() - Vec3(0, 1, 0)).norm(), 0.0, 1e-15);
  EXPECT_TRUE(c.crosses(Vec3(0.5, 1, 0), Vec3(0.5, 3, 0)));
  EXPECT_TRUE(c.crosses(Vec3(0.5, 3, 0), Vec3(0.5, 1, 0)));     // either direction
  EXPECT_TRUE(c.crosses(Vec3(-0.5, 1, 0), Vec3(1.5, 3.5, 0)));  // oblique, crossing at x = 0.3
  EXPECT_FALSE(c.crosses(Vec3(0.5, 2.5, 0), Vec3(1.5, 3, 0)));  // same side
  EXPECT_FALSE(c.crosses(Vec3(0.5, 1.0, 0), Vec3(1.5, 1.9, 0)));
  EXPECT_FALSE(c.crosses(Vec3(3, 1, 0), Vec3(3, 3, 0)));      // beyond the end
  EXPECT_FALSE(c.crosses(Vec3(-1, 1, 0), Vec3(-1, 3, 0)));    // before the start
  EXPECT_FALSE(c.crosses(Vec3(2.5, 1, 0), Vec3(3.5, 3, 0)));  // would cross the line at x = 3
  EXPECT_TRUE(c.crosses(Vec3(2, 1, 0), Vec3(2, 3, 0)));       // through the end point (closed)
  EXPECT_FALSE(c.crosses(Vec3(2.001, 1, 0), Vec3(2.001, 3, 0)));
  EXPECT_TRUE(c.crosses(Vec3(0.5, 2, 0), Vec3(0.5, 3, 0)));  // touching counts
  EXPECT_FALSE(c.crosses(Vec3(0, 2, 0), Vec3(1, 2, 0)));     // lying in the cut
  // A tilted cut from (0,0) to (2,2).
  const Cut d = cut2(Vec3(0, 0, 0), Vec3(2, 2, 0));
  EXPECT_TRUE(d.crosses(Vec3(0, 1.5, 0), Vec3(1.5, 0, 0)));
  EXPECT_FALSE(d.crosses(Vec3(2, 3.5, 0), Vec3(3.5, 2, 0)));
}

TEST(MeshCut, Crosses3D) {
  const Cut c = cut3(Vec3(0, 0, 2), Vec3(2, 0, 0), Vec3(0, 4, 0));
  EXPECT_NEAR((c.normal() - Vec3(0, 0, 1)).norm(), 0.0, 1e-15);
  EXPECT_TRUE(c.crosses(Vec3(1, 1, 1), Vec3(1, 1, 3)));
  EXPECT_TRUE(c.crosses(Vec3(0.5, 0.5, 1), Vec3(1.5, 3.5, 3)));  // through (1, 2, 2)
  EXPECT_FALSE(c.crosses(Vec3(1, 1, 2.5), Vec3(1, 1, 3)));
  EXPECT_FALSE(c.crosses(Vec3(3, 1, 1), Vec3(3, 1, 3)));  // beyond edge1
  EXPECT_FALSE(c.crosses(Vec3(1, 5, 1), Vec3(1, 5, 3)));  // beyond edge2
  EXPECT_FALSE(c.crosses(Vec3(1, -0.1, 1), Vec3(1, -0.1, 3)));
  EXPECT_TRUE(c.crosses(Vec3(2, 4, 1), Vec3(2, 4, 3)));       // corner, closed
  EXPECT_FALSE(c.crosses(Vec3(0.5, 1, 2), Vec3(1.5, 1, 2)));  // in the plane
  // A sheared parallelogram: origin 0, edges (1,0,0) and (1,1,0) in z = 0.
  const Cut p = cut3(Vec3::Zero(), Vec3(1, 0, 0), Vec3(1, 1, 0));
  EXPECT_TRUE(p.crosses(Vec3(1.2, 0.5, -1), Vec3(1.2, 0.5, 1)));    // s = 0.7, t = 0.5
  EXPECT_FALSE(p.crosses(Vec3(0.2, 0.5, -1), Vec3(0.2, 0.5, 1)));   // s = -0.3, inside the bounding box
  EXPECT_TRUE(p.crosses(Vec3(1.9, 0.95, -1), Vec3(1.9, 0.95, 1)));  // s = 0.95, t = 0.95
  EXPECT_FALSE(p.crosses(Vec3(1.9, 1.05, -1), Vec3(1.9, 1.05, 1)));
}

TEST(MeshCut, Crosses1D) {
  Cut c;
  c.dim = 1;
  c.origin = Vec3(2, 0, 0);
  EXPECT_TRUE(c.crosses(Vec3(1, 0, 0), Vec3(3, 0, 0)));
  EXPECT_TRUE(c.crosses(Vec3(3, 0, 0), Vec3(1, 0, 0)));
  EXPECT_FALSE(c.crosses(Vec3(2.5, 0, 0), Vec3(3, 0, 0)));
  EXPECT_FALSE(c.crosses(Vec3(0, 0, 0), Vec3(1.5, 0, 0)));
}

TEST(MeshCut, Contains) {
  const Cut c = cut2(Vec3(0, 2, 0), Vec3(2, 0, 0));
  EXPECT_TRUE(c.contains(Vec3(1, 2, 0), 1e-9));
  EXPECT_TRUE(c.contains(Vec3(0, 2, 0), 1e-9));
  EXPECT_TRUE(c.contains(Vec3(2, 2, 0), 1e-9));
  EXPECT_TRUE(c.contains(Vec3(2 + 1e-10, 2, 0), 1e-9));
  EXPECT_FALSE(c.contains(Vec3(2.1, 2, 0), 1e-9));
  EXPECT_FALSE(c.contains(Vec3(-0.1, 2, 0), 1e-9));
  EXPECT_FALSE(c.contains(Vec3(1, 2 + 1e-6, 0), 1e-9));
  EXPECT_TRUE(c.contains(Vec3(1, 2 + 1e-6, 0), 1e-5));
  const Cut h = cut3(Vec3(0, 0, 2), Vec3(2, 0, 0), Vec3(0, 4, 0));
  EXPECT_TRUE(h.contains(Vec3(1, 3, 2), 1e-9));
  EXPECT_TRUE(h.contains(Vec3(2, 4, 2), 1e-9));
  EXPECT_FALSE(h.contains(Vec3(1, 3, 2.01), 1e-9));
  EXPECT_FALSE(h.contains(Vec3(2.5, 3, 2), 1e-9));
  EXPECT_FALSE(h.contains(Vec3(1, 4.5, 2), 1e-9));
  const Cut p = cut3(Vec3::Zero(), Vec3(1, 0, 0), Vec3(1, 1, 0));
  EXPECT_TRUE(p.contains(Vec3(1.5, 0.5, 0), 1e-9));
  EXPECT_FALSE(p.contains(Vec3(0.2, 0.5, 0), 1e-9));
  Cut b;
  b.dim = 1;
  b.origin = Vec3(2, 0, 0);
  EXPECT_TRUE(b.contains(Vec3(2 + 1e-10, 0, 0), 1e-9));
  EXPECT_FALSE(b.contains(Vec3(2.1, 0, 0), 1e-9));
}

}  // namespace
}  // namespace perimorph::mesh
