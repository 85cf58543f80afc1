// [[node_set]] at model build time: a box selects the mesh nodes within it
// (with a tolerance, so point and line boxes work), both copies of a node
// split by a cut, and an empty selection is an error naming the set and box.
// Cases are parsed from case-file text, as the CLI does.

#include "perimorph/casefile/parse_case.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/run/static_run.hpp"
#include "perimorph/setup/boundary_conditions.hpp"
#include "perimorph/setup/discretization.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

namespace perimorph {
namespace {

/// A 48 × 24 plate with 8 × 4 cells (node spacing 6): 9 × 5 nodes.
const std::string kPlate = R"(
[mesh]
dim = 2
lower = [0, 0]
upper = [48, 24]
cells = [8, 4]

[[material]]
name = "steel"
E = 200
nu = 0.3

[output]
vtu = false
)";

std::string node_set(const std::string& name, const std::string& lower, const std::string& upper) {
  return "\n[[node_set]]\nname = \"" + name + "\"\nlower = " + lower + "\nupper = " + upper + "\n";
}

mesh::Mesh mesh_of(const std::string& text) {
  return setup::build_mesh(casefile::parse_case_string(text, "sets.toml"));
}

std::string build_error(const std::string& text) {
  try {
    mesh_of(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return {};
}

bool contains(const std::string& haystack, const std::string& needle) {
  return haystack.find(needle) != std::string::npos;
}

TEST(DriverNodeSet, PointBoxSelectsOneNode) {
  const auto m =
      mesh_of(kPlate + node_set("pin", "[23.9, -0.1]", "[24.1, 0.1]") +
              node_set("exact", "[24, 0]", "[24, 0]") + node_set("corner", "[48, 24]", "[48, 24]"));
  ASSERT_EQ(m.node_sets.count("pin"), 1u);
  const auto& pin = m.node_sets.at("pin");
  ASSERT_EQ(pin.size(), 1u);
  EXPECT_EQ(m.node(pin[0]), Vec3(24, 0, 0));
  // A degenerate (point) box hits the node within the tolerance.
  EXPECT_EQ(m.node_sets.at("exact"), pin);
  ASSERT_EQ(m.node_sets.at("corner").size(), 1u);
  EXPECT_EQ(m.node(m.node_sets.at("corner")[0]), Vec3(48, 24, 0));
  EXPECT_EQ(m.nodes_of_set("pin"), pin);
}

TEST(DriverNodeSet, LineBoxSelectsAnEdgeRow) {
  const auto m =
      mesh_of(kPlate + node_set("bottom", "[0, 0]", "[48, 0]") + node_set("wide", "[-5, -0.5]", "[53, 0.5]") +
              node_set("column", "[12, 0]", "[12, 24]"));
  const auto& bottom = m.node_sets.at("bottom");
  EXPECT_EQ(bottom.size(), 9u);
  std::vector<Index> ymin = m.node_sets.at("ymin");
  std::sort(ymin.begin(), ymin.end());
  EXPECT_EQ(bottom, ymin);
  EXPECT_EQ(m.node_sets.at("wide"), bottom);
  const auto& column = m.node_sets.at("column");
  EXPECT_EQ(column.size(), 5u);
  for (Index n : column) EXPECT_EQ(m.node(n).x(), 12.0);
}

TEST(DriverNodeSet, BothCopiesOfASplitNode) {
  // An edge crack from the left edge to the centre splits the nodes on
  // y = 12 with 0 <= x < 24 (the tip at x = 24 is not split).
  const std::string text = kPlate + "\n[[mesh.cut]]\nfrom = [0, 12]\nto = [24, 12]\n" +
                           node_set("lips", "[12, 12]", "[12, 12]") +
                           node_set("tip", "[24, 12]", "[24, 12]") + node_set("row", "[0, 12]", "[48, 12]");
  const auto m = mesh_of(text);
  const auto& lips = m.node_sets.at("lips");
  ASSERT_EQ(lips.size(), 2u);
  EXPECT_NE(lips[0], lips[1]);
  EXPECT_EQ(m.node(lips[0]), Vec3(12, 12, 0));
  EXPECT_EQ(m.node(lips[1]), Vec3(12, 12, 0));
  EXPECT_EQ(m.node_sets.at("tip").size(), 1u);
  EXPECT_EQ(m.node_sets.at("row").size(), 9u + 4u);  // x = 0, 6, 12, 18 twice
}

TEST(DriverNodeSet, ThreeDimensionalEdgeAndOneDimensionalPoint) {
  const std::string block = R"(
[mesh]
dim = 3
lower = [0, 0, 0]
upper = [2, 3, 4]
cells = [2, 3, 4]

[[material]]
name = "steel"
E = 200
nu = 0.3
)";
  const auto m3 = mesh_of(block + node_set("edge", "[0, 0, 0]", "[0, 0, 4]") +
                          node_set("point", "[1, 1, 1]", "[1, 1, 1]"));
  EXPECT_EQ(m3.node_sets.at("edge").size(), 5u);
  ASSERT_EQ(m3.node_sets.at("point").size(), 1u);
  EXPECT_EQ(m3.node(m3.node_sets.at("point")[0]), Vec3(1, 1, 1));

  const std::string bar = R"(
[mesh]
dim = 1
lower = [0]
upper = [10]
cells = [5]

[[material]]
name = "steel"
E = 200
nu = 0.3
)";
  const auto m1 = mesh_of(bar + node_set("middle", "[4]", "[4]") + node_set("inner", "[1]", "[9]"));
  EXPECT_EQ(m1.node_sets.at("middle").size(), 1u);
  EXPECT_EQ(m1.node_sets.at("inner").size(), 4u);  // x = 2, 4, 6, 8
}

TEST(DriverNodeSet, EmptySelectionIsAnError) {
  // Inside the mesh but between nodes (spacing 6).
  std::string msg = build_error(kPlate + node_set("pin", "[1, 1]", "[2, 2]"));
  EXPECT_TRUE(contains(msg,
                       "sets.toml:16:1: key 'node_set[1]': node set 'pin' (box [1, 1] to [2, 2]) selects no "
                       "mesh node"))
      << msg;
  EXPECT_TRUE(contains(msg, "the mesh spans [0, 0] to [48, 24]")) << msg;
  // Just outside the tolerance of the node at x = 24.
  msg = build_error(kPlate + node_set("off", "[24.001, 0]", "[24.001, 0]"));
  EXPECT_TRUE(contains(msg, "node set 'off' (box [24.001, 0] to [24.001, 0]) selects no mesh node")) << msg;
  // Outside the mesh.
  msg = build_error(kPlate + node_set("far", "[60, 0]", "[70, 24]"));
  EXPECT_TRUE(contains(msg, "node set 'far'")) << msg;
  // The whole model fails the same way.
  EXPECT_THROW(setup::build_discretization(
                   casefile::parse_case_string(kPlate + node_set("pin", "[1, 1]", "[2, 2]"), "sets.toml")),
               InputError);
}

TEST(DriverNodeSet, ProgrammaticClashWithAMeshSetIsAnError) {
  // The parser rejects such names; a config built in code is checked too.
  auto config = casefile::parse_case_string(kPlate, "sets.toml");
  casefile::NodeSetSpec s;
  s.name = "xmin";
  s.lower = Vec3(0, 0, 0);
  s.upper = Vec3(0, 24, 0);
  s.where = {"sets.toml", 3, 1, "node_set[1]"};
  config.node_sets.push_back(s);
  try {
    setup::build_mesh(config);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_TRUE(
        contains(e.what(), "sets.toml:3:1: key 'node_set[1]': node set 'xmin': the mesh already has a set"))
        << e.what();
  }
}

TEST(DriverNodeSet, PinRemovesTheRigidBodyMotion) {
  // Bottom edge on rollers (uy = 0), its middle node pinned in x, the top
  // edge pulled: solvable only because the pin removes the x translation;
  // by symmetry the pinned node does not move.
  const std::string text = kPlate + node_set("pin", "[23.9, -0.1]", "[24.1, 0.1]") +
                           "\n[[dirichlet]]\nset = \"ymin\"\nuy = 0\n"
                           "\n[[dirichlet]]\nset = \"pin\"\nux = 0\n"
                           "\n[[traction]]\nset = \"ymax\"\nvalue = [0, 1]\n"
                           "\n[solver]\nrtol = 1e-12\n";
  const auto model = setup::build_discretization(casefile::parse_case_string(text, "pin.toml"));
  const auto bc = setup::build_dirichlet(model);
  EXPECT_EQ(bc.dofs.size(), 9u + 1u);
  const auto sets = setup::reaction_sets(model);
  ASSERT_EQ(sets.size(), 2u);
  EXPECT_EQ(sets[1].name, "pin");
  ASSERT_EQ(sets[1].dof_nodes.size(), 1u);
  EXPECT_EQ(model.dofmap.node_coordinate(model.mesh, sets[1].dof_nodes[0]), Vec3(24, 0, 0));

  const auto dir = std::filesystem::temp_directory_path() / "perimorph_test_node_set_pin";
  std::filesystem::remove_all(dir);
  const auto run = run::run_static(model, {dir.string(), true});
  // Uniaxial stress σ_yy = 1 (plane strain): ε_yy = (1 − ν²)/E, top edge at 24 ε_yy.
  const std::vector<Index> corner{model.mesh.node_sets.at("ymax").back()};
  const Index top_right = model.dofmap.dof_nodes_of_mesh_nodes(corner)[0];
  EXPECT_NEAR(run.displacement[static_cast<std::size_t>(2 * top_right + 1)], 24 * (1 - 0.09) / 200, 1e-9);
  EXPECT_NEAR(run.reactions[1].x(), 0.0, 1e-9);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace perimorph
