// The Gmsh reader (mesh/gmsh_reader.hpp) on small files made with the Gmsh
// CLI from the .geo files beside them (tests/data/gmsh): cells, node order,
// sets from physical groups, formats 4.1 and 2.2, and the errors for files
// perimorph cannot use.

#include "perimorph/mesh/gmsh_reader.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/mesh/box.hpp"
#include "perimorph/mesh/cut.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace perimorph::mesh {
namespace {

std::string data(const std::string& name) {
  return std::string(PERIMORPH_TEST_DATA) + "/gmsh/" + name;
}

std::string error_of(const std::string& name, int dim) {
  try {
    read_gmsh(data(name), dim);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

/// Gmsh's transfinite nodes carry round-off (0.4999999999986921 for 1/2):
/// positions are compared to this tolerance.
constexpr double kGmshRoundOff = 1e-11;

TEST(GmshReader, StructuredRectangleIsTheBoxGrid) {
  const Mesh g = read_gmsh(data("rectangle.msh"), 2);
  const Mesh b = make_box({2, Vec3::Zero(), Vec3(2, 1, 0), {8, 4, 1}});
  ASSERT_EQ(g.num_cells(), 32);
  ASSERT_EQ(g.num_nodes(), 45);
  EXPECT_FALSE(g.structure.has_value());
  // Every Gmsh cell has the corners of one box cell.
  for (Index c = 0; c < g.num_cells(); ++c) {
    const Vec3 x0 = g.node(g.cell(c)[0]);
    const auto i = static_cast<Index>(std::lround(x0.x() / 0.25));
    const auto j = static_cast<Index>(std::lround(x0.y() / 0.25));
    const auto box_cell = b.cell(i + 8 * j);
    for (int a = 0; a < 4; ++a)
      EXPECT_LT(
          (g.node(g.cell(c)[static_cast<std::size_t>(a)]) - b.node(box_cell[static_cast<std::size_t>(a)]))
              .norm(),
          kGmshRoundOff);
  }
  // Lexicographic local order: node 1 is +x of node 0, node 2 is +y of node 0.
  for (Index c = 0; c < g.num_cells(); ++c) {
    const auto n = g.cell(c);
    EXPECT_GT(g.node(n[1]).x(), g.node(n[0]).x());
    EXPECT_GT(g.node(n[2]).y(), g.node(n[0]).y());
    EXPECT_NEAR(g.node(n[3]).x(), g.node(n[1]).x(), kGmshRoundOff);
    EXPECT_NEAR(g.node(n[3]).y(), g.node(n[2]).y(), kGmshRoundOff);
  }
}

TEST(GmshReader, PhysicalGroupsBecomeSets) {
  const Mesh g = read_gmsh(data("rectangle.msh"), 2);
  ASSERT_TRUE(g.face_sets.count("left"));
  EXPECT_EQ(g.face_sets.at("left").size(), 4u);
  EXPECT_EQ(g.face_sets.at("top").size(), 8u);
  for (Index n : g.nodes_of_set("left")) EXPECT_EQ(g.node(n).x(), 0.0);  // ends of lines are exact
  EXPECT_EQ(g.nodes_of_set("right").size(), 5u);
  for (const CellFace& f : g.face_sets.at("right")) EXPECT_EQ(f.face, 1);  // +x faces
  ASSERT_TRUE(g.node_sets.count("origin"));
  ASSERT_EQ(g.node_sets.at("origin").size(), 1u);
  EXPECT_EQ(g.node(g.node_sets.at("origin")[0]), Vec3::Zero());
  EXPECT_EQ(g.cell_sets.at("body").size(), 32u);
  EXPECT_EQ(g.cell_sets.at("all").size(), 32u);
  EXPECT_EQ(g.face_sets.at("boundary").size(), 24u);
  EXPECT_EQ(g.node_sets.at("boundary").size(), 24u);
}

TEST(GmshReader, Format22GivesTheSameMesh) {
  const Mesh a = read_gmsh(data("rectangle.msh"), 2);
  const Mesh b = read_gmsh(data("rectangle_v22.msh"), 2);
  EXPECT_EQ(a.nodes(), b.nodes());
  EXPECT_EQ(a.connectivity(), b.connectivity());
  EXPECT_EQ(a.face_sets, b.face_sets);
  EXPECT_EQ(a.node_sets, b.node_sets);
  EXPECT_EQ(a.cell_sets, b.cell_sets);
}

TEST(GmshReader, HexahedraAndTheirGroups) {
  const Mesh g = read_gmsh(data("block.msh"), 3);
  ASSERT_EQ(g.num_cells(), 16);
  EXPECT_EQ(g.num_nodes(), 5 * 3 * 3);
  EXPECT_EQ(g.cell_sets.at("soft").size(), 8u);
  EXPECT_EQ(g.cell_sets.at("hard").size(), 8u);
  for (Index c : g.cell_sets.at("soft")) EXPECT_LT(g.cell_centroid(c).x(), 1.0);
  for (Index c : g.cell_sets.at("hard")) EXPECT_GT(g.cell_centroid(c).x(), 1.0);
  ASSERT_EQ(g.face_sets.at("xmin_face").size(), 4u);
  for (Index n : g.nodes_of_set("xmin_face")) EXPECT_EQ(g.node(n).x(), 0.0);
  EXPECT_EQ(g.face_sets.at("top_face").size(), 8u);
  for (Index n : g.nodes_of_set("top_face")) EXPECT_EQ(g.node(n).z(), 1.0);
  EXPECT_EQ(g.node_sets.at("edge").size(), 3u);  // a physical curve in 3D: its nodes
  EXPECT_EQ(g.face_sets.at("boundary").size(), 2u * (8 + 4 + 8));
  for (Index c = 0; c < g.num_cells(); ++c) {  // lexicographic order: +x, +y, +z neighbours
    const auto n = g.cell(c);
    EXPECT_GT(g.node(n[1]).x(), g.node(n[0]).x());
    EXPECT_GT(g.node(n[2]).y(), g.node(n[0]).y());
    EXPECT_GT(g.node(n[4]).z(), g.node(n[0]).z());
  }
}

TEST(GmshReader, PrecrackGroupSplitsItsNodes) {
  Mesh g = read_gmsh(data("edge_crack.msh"), 2);
  ASSERT_TRUE(g.face_sets.count("crack"));
  const Index nodes = g.num_nodes();
  const CutReport r = split_along_faces(g, g.face_sets.at("crack"));
  EXPECT_EQ(r.faces_cut, 2);    // two cell edges along the crack
  EXPECT_EQ(r.nodes_split, 2);  // at x = 0 (the crack mouth) and x = 0.5; the tip x = 1 stays whole
  EXPECT_EQ(g.num_nodes(), nodes + 2);
  ASSERT_EQ(g.cuts.size(), 2u);
  EXPECT_TRUE(g.cuts[0].crosses(Vec3(0.25, 0.9, 0), Vec3(0.25, 1.1, 0)));
  EXPECT_FALSE(g.cuts[0].crosses(Vec3(1.5, 0.9, 0), Vec3(1.5, 1.1, 0)));
}

TEST(GmshReader, ErrorsSayWhatToDo) {
  EXPECT_NE(error_of("missing.msh", 2).find("no such mesh file"), std::string::npos)
      << error_of("missing.msh", 2);
  EXPECT_NE(error_of("rectangle.geo", 2).find("mesh it first"), std::string::npos)
      << error_of("rectangle.geo", 2);
  EXPECT_NE(error_of("version3.msh", 2).find("version \"3.0\""), std::string::npos)
      << error_of("version3.msh", 2);
  EXPECT_NE(error_of("version3.msh", 2).find("-format msh41"), std::string::npos)
      << error_of("version3.msh", 2);
  EXPECT_NE(error_of("not_a_mesh.msh", 2).find("$MeshFormat"), std::string::npos)
      << error_of("not_a_mesh.msh", 2);
  const std::string tri = error_of("triangles.msh", 2);
  EXPECT_NE(tri.find("Triangle"), std::string::npos) << tri;
  EXPECT_NE(tri.find("Recombine"), std::string::npos) << tri;
  const std::string cw = error_of("clockwise.msh", 2);
  EXPECT_NE(cw.find("inverted"), std::string::npos) << cw;
  EXPECT_NE(cw.find("counter-clockwise"), std::string::npos) << cw;
  EXPECT_NE(error_of("rectangle.msh", 3).find("no element of dimension 3"), std::string::npos)
      << error_of("rectangle.msh", 3);
  EXPECT_NE(error_of("block.msh", 2).find("z = 0"), std::string::npos) << error_of("block.msh", 2);
}

}  // namespace
}  // namespace perimorph::mesh
