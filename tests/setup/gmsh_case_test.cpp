// Cases on Gmsh meshes ([mesh] type = "gmsh"): the whole pipeline gives the
// box mesh's answers on a Gmsh mesh of the same grid (elastic hybrid, and a
// pre-crack read as a physical curve against the box's [[mesh.cut]]), and the
// case errors that involve the mesh file name the key.

#include "perimorph/casefile/parse_case.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/run/static_run.hpp"
#include "perimorph/setup/discretization.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace perimorph {
namespace {

/// A case file "in" tests/data/gmsh, so that `file` is found beside it.
casefile::CaseConfig parse(const std::string& text) {
  return casefile::parse_case_string(text, std::string(PERIMORPH_TEST_DATA) + "/gmsh/case.toml");
}

std::string scratch(const std::string& name) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("perimorph_gmsh_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  return dir.string();
}

run::RunSummary solve(const std::string& text, const std::string& name) {
  const auto model = setup::build_discretization(parse(text));
  return run::run_static(model, {scratch(name), true});
}

// An elastic hybrid on the 2 x 1 rectangle: α = 1 in a disk, morphing around it.
const std::string kPhysics = R"(
[model]
plane = "stress"
[[material]]
name = "m"
E = 1000.0
[nonlocal]
kernel = "gaussian"
horizon = 0.75
length = 0.25
quadrature = 2
[[alpha.region]]
shape = "ball"
center = [1.0, 0.5]
radius = 0.3
transition = 0.3
[loading]
increments = 1
[solver]
petsc_options = "-ksp_type preonly -pc_type cholesky"
[output]
vtu = false
)";

TEST(GmshCase, RectangleGivesTheBoxAnswers) {
  const auto box = solve(R"(
[mesh]
dim = 2
lower = [0.0, 0.0]
upper = [2.0, 1.0]
cells = [8, 4]
[[dirichlet]]
set = "xmin"
ux = 0.0
uy = 0.0
[[dirichlet]]
set = "xmax"
ux = 0.01
)" + kPhysics,
                         "box");
  const auto gmsh = solve(R"(
[mesh]
type = "gmsh"
file = "rectangle.msh"
dim = 2
[[dirichlet]]
set = "left"
ux = 0.0
uy = 0.0
[[dirichlet]]
set = "right"
ux = 0.01
)" + kPhysics,
                          "gmsh");
  ASSERT_GT(box.strain_energy, 0.0);
  // Gmsh's nodes differ from the grid by round-off (1e-12): answers agree to about that.
  EXPECT_NEAR(gmsh.strain_energy, box.strain_energy, 1e-9 * box.strain_energy);
  ASSERT_EQ(gmsh.reactions.size(), box.reactions.size());
  for (std::size_t i = 0; i < box.reactions.size(); ++i)
    EXPECT_NEAR((gmsh.reactions[i] - box.reactions[i]).norm(), 0.0, 1e-9 * box.reactions[i].norm());
}

// A purely non-local plate (DG, α ≡ 1) with an edge crack to its middle, pulled apart.
const std::string kCrackPhysics = R"(
[[material]]
name = "m"
E = 1000.0
[nonlocal]
kernel = "constant"
horizon = 0.75
quadrature = 2
discretization = "discontinuous"
[alpha]
value = 1.0
[loading]
increments = 1
[solver]
petsc_options = "-ksp_type preonly -pc_type lu"
[output]
vtu = false
)";

TEST(GmshCase, PrecrackGroupActsAsTheBoxCut) {
  const auto box = solve(R"(
[mesh]
dim = 2
lower = [0.0, 0.0]
upper = [2.0, 2.0]
cells = [4, 4]
[[mesh.cut]]
from = [0.0, 1.0]
to = [1.0, 1.0]
[[dirichlet]]
set = "ymin"
ux = 0.0
uy = 0.0
[[dirichlet]]
set = "ymax"
ux = 0.0
uy = 0.01
)" + kCrackPhysics,
                         "crack_box");
  const auto gmsh = solve(R"(
[mesh]
type = "gmsh"
file = "edge_crack.msh"
dim = 2
precrack = "crack"
[[dirichlet]]
set = "bottom"
ux = 0.0
uy = 0.0
[[dirichlet]]
set = "top"
ux = 0.0
uy = 0.01
)" + kCrackPhysics,
                          "crack_gmsh");
  const auto uncut = solve(R"(
[mesh]
type = "gmsh"
file = "edge_crack.msh"
dim = 2
[[dirichlet]]
set = "bottom"
ux = 0.0
uy = 0.0
[[dirichlet]]
set = "top"
ux = 0.0
uy = 0.01
)" + kCrackPhysics,
                           "uncut_gmsh");
  EXPECT_NEAR(gmsh.strain_energy, box.strain_energy, 1e-9 * box.strain_energy);
  EXPECT_LT(gmsh.strain_energy, 0.9 * uncut.strain_energy);  // the crack softens the plate
}

TEST(GmshCase, PrecrackSurfaceActsAsTheBoxCut3D) {
  const std::string physics = R"(
[[material]]
name = "m"
E = 1000.0
[nonlocal]
kernel = "constant"
horizon = 0.75
quadrature = 2
discretization = "discontinuous"
[alpha]
value = 1.0
[loading]
increments = 1
[solver]
petsc_options = "-ksp_type preonly -pc_type lu"
[output]
vtu = false
)";
  const std::string pull = R"(
ux = 0.0
uy = 0.01
uz = 0.0
)";
  const auto box = solve(R"(
[mesh]
dim = 3
lower = [0.0, 0.0, 0.0]
upper = [2.0, 2.0, 1.0]
cells = [4, 4, 2]
[[mesh.cut]]
origin = [0.0, 1.0, 0.0]
edge1 = [1.0, 0.0, 0.0]
edge2 = [0.0, 0.0, 1.0]
[[dirichlet]]
set = "ymin"
ux = 0.0
uy = 0.0
uz = 0.0
[[dirichlet]]
set = "ymax"
)" + pull + physics,
                         "crack3_box");
  const auto gmsh = solve(R"(
[mesh]
type = "gmsh"
file = "edge_crack_3d.msh"
dim = 3
precrack = "crack"
[[dirichlet]]
set = "bottom"
ux = 0.0
uy = 0.0
uz = 0.0
[[dirichlet]]
set = "top"
)" + pull + physics,
                          "crack3_gmsh");
  ASSERT_GT(box.strain_energy, 0.0);
  EXPECT_NEAR(gmsh.strain_energy, box.strain_energy, 1e-9 * box.strain_energy);
}

std::string case_error(const std::string& text) {
  try {
    run::prepare_run(setup::build_discretization(parse(text)));
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

TEST(GmshCase, ErrorsNameTheKey) {
  const std::string head = "[mesh]\ntype = \"gmsh\"\ndim = 2\n";
  const std::string material = "[[material]]\nname = \"m\"\nE = 1.0\nnu = 0.25\n";
  const std::string missing = case_error(head + "file = \"nowhere.msh\"\n" + material);
  EXPECT_TRUE(contains(missing, "case.toml:4")) << missing;
  EXPECT_TRUE(contains(missing, "no such mesh file")) << missing;
  const std::string crack = case_error(head + "file = \"rectangle.msh\"\nprecrack = \"slit\"\n" + material);
  EXPECT_TRUE(contains(crack, "precrack")) << crack;
  EXPECT_TRUE(contains(crack, "left")) << crack;  // the face groups it has
  const std::string region =
      case_error(head + "file = \"rectangle.msh\"\n[[region]]\nname = \"r\"\nset = \"core\"\n" + material);
  EXPECT_TRUE(contains(region, "no cell set \"core\"")) << region;
  EXPECT_TRUE(contains(region, "body")) << region;
  const std::string set =
      case_error(head + "file = \"rectangle.msh\"\n" + material + "[[dirichlet]]\nset = \"lft\"\nux = 0.0\n");
  EXPECT_TRUE(contains(set, "no set named 'lft' (did you mean 'left'?)")) << set;
  EXPECT_TRUE(contains(set, "Gmsh file's physical groups")) << set;
  try {
    parse(head + "file = \"rectangle.msh\"\ncells = [4, 4]\n" + material);
    ADD_FAILURE() << "cells with type = gmsh accepted";
  } catch (const InputError& e) {
    EXPECT_TRUE(contains(e.what(), "belong to type = \"box\"")) << e.what();
  }
}

TEST(GmshCase, RegionFromAPhysicalGroup) {
  const auto c = parse(R"(
[mesh]
type = "gmsh"
file = "block.msh"
dim = 3
[[region]]
name = "stiff"
set = "hard"
[[material]]
name = "a"
E = 1.0
nu = 0.25
[[material]]
name = "b"
region = "stiff"
E = 2.0
nu = 0.25
)");
  const auto model = setup::build_discretization(c);
  for (Index cell = 0; cell < model.mesh.num_cells(); ++cell)
    EXPECT_EQ(model.mesh.cell_region[static_cast<std::size_t>(cell)],
              model.mesh.cell_centroid(cell).x() > 1 ? 1 : 0);
}

}  // namespace
}  // namespace perimorph
