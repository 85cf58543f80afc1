// Structured box meshes: counts, exact bounds, named sets, cell orientation.
#include "perimorph/mesh/box.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/fem/quadrature.hpp"
#include "perimorph/fem/shape.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <set>
#include <string>
#include <vector>

namespace perimorph::mesh {
namespace {

BoxSpec spec(int dim, Vec3 lower, Vec3 upper, std::array<Index, 3> cells) {
  BoxSpec s;
  s.dim = dim;
  s.lower = lower;
  s.upper = upper;
  s.cells = cells;
  return s;
}

// Non-round bounds so that exactness of the first/last coordinates is a real check.
const Vec3 lo3(0.1, -0.3, 0.7);
const Vec3 hi3(1.3, 2.9, 1.1);

const char* const axis_names[3][2] = {{"xmin", "xmax"}, {"ymin", "ymax"}, {"zmin", "zmax"}};

template <int D>
fem::NodeCoords<D> coords(const Mesh& m, Index c) {
  fem::NodeCoords<D> X;
  for (int a = 0; a < fem::q1_nodes<D>; ++a)
    X.col(a) = m.node(m.cell(c)[static_cast<std::size_t>(a)]).head<D>();
  return X;
}

/// Every cell has positive det J at every 3×3(×3) Gauss point and at the
/// corners, and det J equals the cell volume / 2^D for a box cell.
template <int D>
void expect_positive_jacobians(const Mesh& m, double cell_volume) {
  std::vector<Vec3> points;
  for (const auto& q : fem::gauss_legendre(D, 3)) points.push_back(q.xi);
  for (int a = 0; a < fem::q1_nodes<D>; ++a) {
    Vec3 xi = Vec3::Zero();
    for (int d = 0; d < D; ++d) xi[d] = reference_node_coordinate(a, d);
    points.push_back(xi);
  }
  fem::ShapeGradients<D> g;
  for (Index c = 0; c < m.num_cells(); ++c) {
    const auto X = coords<D>(m, c);
    for (const Vec3& xi : points) {
      const double detJ = fem::q1_physical_gradients<D>(X, xi, g);
      ASSERT_GT(detJ, 0.0) << "cell " << c;
      EXPECT_NEAR(detJ, cell_volume / (1 << D), 1e-12 * cell_volume) << "cell " << c;
    }
  }
}

/// Local node a of each cell sits at corner a of the cell (x fastest).
void expect_lexicographic_cells(const Mesh& m, const Vec3& h) {
  for (Index c = 0; c < m.num_cells(); ++c) {
    const Vec3& x0 = m.node(m.cell(c)[0]);
    for (int a = 0; a < m.nodes_per_cell(); ++a) {
      const Vec3 dx = m.node(m.cell(c)[static_cast<std::size_t>(a)]) - x0;
      for (int d = 0; d < m.dim(); ++d)
        EXPECT_NEAR(dx[d], ((a >> d) & 1) ? h[d] : 0.0, 1e-12)
            << "cell " << c << " node " << a << " axis " << d;
    }
  }
}

/// Face sets: face f = 2d + side on every entry, and all the face's nodes lie
/// exactly on the bounding plane; node sets likewise.
void expect_named_sets(const Mesh& m, const Vec3& lo, const Vec3& hi) {
  for (int d = 0; d < m.dim(); ++d)
    for (int side = 0; side < 2; ++side) {
      const std::string name = axis_names[d][side];
      const double plane = side == 0 ? lo[d] : hi[d];
      ASSERT_TRUE(m.node_sets.count(name)) << name;
      ASSERT_TRUE(m.face_sets.count(name)) << name;
      for (Index n : m.node_sets.at(name)) EXPECT_EQ(m.node(n)[d], plane) << name << " node " << n;
      // Every node on the plane is in the set.
      Index on_plane = 0;
      for (Index n = 0; n < m.num_nodes(); ++n) on_plane += m.node(n)[d] == plane ? 1 : 0;
      EXPECT_EQ(static_cast<Index>(m.node_sets.at(name).size()), on_plane) << name;
      for (const CellFace& cf : m.face_sets.at(name)) {
        EXPECT_EQ(cf.face, 2 * d + side) << name;
        for (int a : face_nodes(m.cell_type(), cf.face))
          EXPECT_EQ(m.node(m.cell(cf.cell)[static_cast<std::size_t>(a)])[d], plane)
              << name << " cell " << cf.cell;
        // The cell lies on the inner side of its face.
        const double inward = m.cell_centroid(cf.cell)[d] - plane;
        EXPECT_TRUE(side == 0 ? inward > 0 : inward < 0) << name;
      }
    }
  for (int d = m.dim(); d < 3; ++d)
    for (int side = 0; side < 2; ++side) {
      EXPECT_FALSE(m.node_sets.count(axis_names[d][side])) << "set for an unused axis";
      EXPECT_FALSE(m.face_sets.count(axis_names[d][side])) << "set for an unused axis";
    }
  // "boundary" = every node with some coordinate on the bounds.
  std::vector<Index> expected;
  for (Index n = 0; n < m.num_nodes(); ++n) {
    bool on = false;
    for (int d = 0; d < m.dim(); ++d) on = on || m.node(n)[d] == lo[d] || m.node(n)[d] == hi[d];
    if (on) expected.push_back(n);
  }
  std::vector<Index> boundary = m.node_sets.at("boundary");
  std::sort(boundary.begin(), boundary.end());
  EXPECT_EQ(boundary, expected);
  // Face set "boundary" is the union of the axis face sets.
  std::set<CellFace> all_faces;
  std::size_t total = 0;
  for (int d = 0; d < m.dim(); ++d)
    for (int side = 0; side < 2; ++side) {
      const auto& fs = m.face_sets.at(axis_names[d][side]);
      all_faces.insert(fs.begin(), fs.end());
      total += fs.size();
    }
  const auto& bf = m.face_sets.at("boundary");
  EXPECT_EQ(bf.size(), total);
  EXPECT_EQ(std::set<CellFace>(bf.begin(), bf.end()), all_faces);
  // Cell set "all".
  std::vector<Index> all(static_cast<std::size_t>(m.num_cells()));
  for (Index c = 0; c < m.num_cells(); ++c) all[static_cast<std::size_t>(c)] = c;
  EXPECT_EQ(m.cell_sets.at("all"), all);
}

TEST(MeshBox, Bar1D) {
  const Vec3 lo(-0.7, 0, 0), hi(2.3, 0, 0);
  const Mesh m = make_box(spec(1, lo, hi, {4, 9, 9}));
  EXPECT_EQ(m.dim(), 1);
  EXPECT_EQ(m.cell_type(), CellType::bar2);
  EXPECT_EQ(m.num_nodes(), 5);
  EXPECT_EQ(m.num_cells(), 4);
  EXPECT_EQ(m.node(0), lo);
  EXPECT_EQ(m.node(4), hi);
  for (Index n = 0; n < m.num_nodes(); ++n) {
    EXPECT_EQ(m.node(n).y(), 0.0);
    EXPECT_EQ(m.node(n).z(), 0.0);
  }
  EXPECT_EQ(m.node_sets.at("xmin"), std::vector<Index>{0});
  EXPECT_EQ(m.node_sets.at("xmax"), std::vector<Index>{4});
  EXPECT_EQ((m.node_sets.at("boundary")), (std::vector<Index>{0, 4}));
  ASSERT_EQ(m.face_sets.at("xmin").size(), 1u);
  EXPECT_EQ(m.face_sets.at("xmin")[0], (CellFace{0, 0}));
  ASSERT_EQ(m.face_sets.at("xmax").size(), 1u);
  EXPECT_EQ(m.face_sets.at("xmax")[0], (CellFace{3, 1}));
  expect_named_sets(m, lo, hi);
  expect_lexicographic_cells(m, Vec3(0.75, 0, 0));
  expect_positive_jacobians<1>(m, 0.75);
  for (Index c = 0; c < m.num_cells(); ++c) EXPECT_NEAR(m.cell_size(c), 0.75, 1e-15);
  EXPECT_EQ(m.cell_region, std::vector<int>(4, 0));
}

TEST(MeshBox, Quad2D) {
  const Vec3 lo(1.0, -1.0, 0.0), hi(4.0, 1.0, 0.0);
  const Mesh m = make_box(spec(2, lo, hi, {3, 2, 7}));
  EXPECT_EQ(m.cell_type(), CellType::quad4);
  EXPECT_EQ(m.num_nodes(), 12);
  EXPECT_EQ(m.num_cells(), 6);
  EXPECT_EQ(m.node(0), lo);
  EXPECT_EQ(m.node(11), hi);
  EXPECT_EQ(m.node(3), Vec3(4.0, -1.0, 0.0));  // x fastest
  EXPECT_EQ(m.node(4), Vec3(1.0, 0.0, 0.0));
  EXPECT_EQ(m.node_sets.at("xmin").size(), 3u);
  EXPECT_EQ(m.node_sets.at("xmax").size(), 3u);
  EXPECT_EQ(m.node_sets.at("ymin").size(), 4u);
  EXPECT_EQ(m.node_sets.at("ymax").size(), 4u);
  EXPECT_EQ(m.node_sets.at("boundary").size(), 12u - 2u);
  EXPECT_EQ(m.face_sets.at("xmin").size(), 2u);
  EXPECT_EQ(m.face_sets.at("ymax").size(), 3u);
  EXPECT_EQ(m.face_sets.at("boundary").size(), 10u);
  EXPECT_EQ(m.cell_sets.at("all").size(), 6u);
  expect_named_sets(m, lo, hi);
  expect_lexicographic_cells(m, Vec3(1.0, 1.0, 0.0));
  expect_positive_jacobians<2>(m, 1.0);
  for (Index n = 0; n < m.num_nodes(); ++n) EXPECT_EQ(m.node(n).z(), 0.0);
}

TEST(MeshBox, Hex3D) {
  const Mesh m = make_box(spec(3, lo3, hi3, {4, 3, 2}));
  EXPECT_EQ(m.cell_type(), CellType::hex8);
  EXPECT_EQ(m.nodes_per_cell(), 8);
  EXPECT_EQ(m.num_nodes(), 60);
  EXPECT_EQ(m.num_cells(), 24);
  EXPECT_EQ(m.connectivity().size(), 24u * 8u);
  EXPECT_EQ(m.node(0), lo3);
  EXPECT_EQ(m.node(59), hi3);
  const auto [blo, bhi] = m.bounding_box();
  EXPECT_EQ(blo, lo3);
  EXPECT_EQ(bhi, hi3);
  EXPECT_EQ(m.node_sets.at("xmin").size(), 12u);  // 4 × 3
  EXPECT_EQ(m.node_sets.at("xmax").size(), 12u);
  EXPECT_EQ(m.node_sets.at("ymin").size(), 15u);  // 5 × 3
  EXPECT_EQ(m.node_sets.at("ymax").size(), 15u);
  EXPECT_EQ(m.node_sets.at("zmin").size(), 20u);  // 5 × 4
  EXPECT_EQ(m.node_sets.at("zmax").size(), 20u);
  EXPECT_EQ(m.node_sets.at("boundary").size(), 60u - 3u * 2u * 1u);  // all minus interior
  EXPECT_EQ(m.face_sets.at("xmin").size(), 6u);                      // 3 × 2
  EXPECT_EQ(m.face_sets.at("ymax").size(), 8u);                      // 4 × 2
  EXPECT_EQ(m.face_sets.at("zmin").size(), 12u);                     // 4 × 3
  EXPECT_EQ(m.face_sets.at("boundary").size(), 52u);
  const Vec3 h = (hi3 - lo3).cwiseQuotient(Vec3(4, 3, 2));
  expect_named_sets(m, lo3, hi3);
  expect_lexicographic_cells(m, h);
  expect_positive_jacobians<3>(m, h.prod());
}

TEST(MeshBox, CellSizeIsLongestEdge) {
  // Cells 0.3 × 0.8 × 0.2: the largest edge, not the diagonal.
  const Mesh m = make_box(spec(3, Vec3::Zero(), Vec3(1.2, 1.6, 0.6), {4, 2, 3}));
  for (Index c = 0; c < m.num_cells(); ++c) EXPECT_NEAR(m.cell_size(c), 0.8, 1e-14);
  const Mesh q = make_box(spec(2, Vec3::Zero(), Vec3(3.0, 0.5, 0.0), {2, 5, 1}));
  for (Index c = 0; c < q.num_cells(); ++c) EXPECT_NEAR(q.cell_size(c), 1.5, 1e-14);
  for (Index c = 0; c < q.num_cells(); ++c) {
    const Vec3 x = q.cell_centroid(c);
    EXPECT_NEAR(x.x(), 0.75 + 1.5 * static_cast<double>(c % 2), 1e-14);
    EXPECT_NEAR(x.y(), 0.05 + 0.1 * static_cast<double>(c / 2), 1e-14);
  }
}

TEST(MeshBox, NodesOfSet) {
  Mesh m = make_box(spec(2, Vec3::Zero(), Vec3(3, 2, 0), {3, 2, 1}));
  // Node set.
  EXPECT_EQ(m.nodes_of_set("xmin"), (std::vector<Index>{0, 4, 8}));
  EXPECT_EQ(m.nodes_of_set("ymax"), (std::vector<Index>{8, 9, 10, 11}));
  // Face set only: the nodes of its faces, sorted and unique.
  m.face_sets["top_middle"] = {{4, 3}, {5, 3}};  // cells (1,1), (2,1), face +y
  EXPECT_EQ(m.nodes_of_set("top_middle"), (std::vector<Index>{9, 10, 11}));
  // The face-set path agrees with the node set of the same name.
  const std::vector<Index> xmax = m.node_sets.at("xmax");
  m.node_sets.erase("xmax");
  EXPECT_EQ(m.nodes_of_set("xmax"), xmax);
  // Cell sets.
  m.cell_sets["first"] = {0};
  EXPECT_EQ(m.nodes_of_set("first"), (std::vector<Index>{0, 1, 4, 5}));
  EXPECT_EQ(m.nodes_of_set("all").size(), 12u);
  // Unknown name: InputError naming the known sets.
  try {
    (void)m.nodes_of_set("xmiddle");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("xmiddle"), std::string::npos) << msg;
    for (const char* known : {"xmin", "xmax", "ymin", "ymax", "boundary", "all", "top_middle", "first"})
      EXPECT_NE(msg.find(known), std::string::npos) << known << " missing from: " << msg;
  }
  EXPECT_THROW((void)m.nodes_of_set("zmin"), InputError);  // 2D box has no z sets
  const auto names = m.set_names();
  EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));
  EXPECT_EQ(std::adjacent_find(names.begin(), names.end()), names.end());
}

/// A cell of the box alone has the box's corners bit for bit (awkward
/// bounds, so that the expression matters), in the mesh's order.
TEST(MeshBox, ACellAloneHasTheBoxsCornersBitForBit) {
  for (int dim : {1, 2, 3}) {
    const Mesh m = make_box({dim, Vec3(-0.3, 0.1, 1.7), Vec3(2.9, 1.3, 2.3), {7, 3, 5}});
    ASSERT_TRUE(m.structure.has_value());
    for (Index c = 0; c < m.num_cells(); ++c) {
      const Mesh one = box_cell_mesh(*m.structure, dim, c);
      ASSERT_EQ(one.num_cells(), 1);
      for (std::size_t a = 0; a < m.cell(c).size(); ++a)
        EXPECT_EQ(std::memcmp(one.node(one.cell(0)[a]).data(), m.node(m.cell(c)[a]).data(), sizeof(Vec3)), 0)
            << "dim " << dim << ", cell " << c << ", corner " << a;
    }
  }
}

}  // namespace
}  // namespace perimorph::mesh
