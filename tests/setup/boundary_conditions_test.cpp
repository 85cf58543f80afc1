// What a boundary condition reaches (setup/boundary_conditions.hpp): with DG
// of degree 0 (one node per cell, at its centroid, copying no mesh node) a
// node or face set reaches the centroid nodes of the cells touching it, so
// Dirichlet values, reactions, tractions and body forces act on them; an
// unknown set name names the closest one; a set that reaches no dof is an
// error. Before, a [[dirichlet]] on `xmin` with α ≡ 1 reached nothing and the
// run gave u = 0, and tractions and body forces on DG0 cells read past the
// cell's one node.

#include "perimorph/setup/boundary_conditions.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/mesh/mesh.hpp"
#include "perimorph/run/static_run.hpp"
#include "perimorph/setup/discretization.hpp"
#include "support/cases.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numeric>
#include <string>

namespace perimorph {
namespace {

using testing::fixed;

/// A 4 × 2 plate of 8 × 4 cells (h = 0.5), fully non-local (α ≡ 1), DG degree 0.
casefile::CaseConfig dg0_plate() {
  auto c = testing::box_case(2, {8, 4, 1}, Vec3(4.0, 2.0, 1.0), 1.0, 0.25);
  testing::add_nonlocal(c, casefile::KernelKind::constant, 1.0, 0.0, 2,
                        casefile::Discretization::discontinuous_constant);
  c.materials[0].nu = std::numeric_limits<double>::quiet_NaN();
  c.alpha.value = 1.0;
  c.model.thickness = 0.5;
  return c;
}

/// The cells of column i (x index) of the 8 × 4 plate.
std::vector<Index> column(Index i) {
  std::vector<Index> cells;
  for (Index j = 0; j < 4; ++j) cells.push_back(i + 8 * j);
  return cells;
}

TEST(DriverBoundaryConditions, FaceSetReachesTheDegreeZeroCellsTouchingIt) {
  const auto model = setup::build_discretization(dg0_plate());
  ASSERT_EQ(model.dofmap.num_nodes(), 32);  // one node per cell, none at a vertex
  const auto nodes = setup::set_dof_nodes(model, "xmin", {});
  std::vector<Index> expected;
  for (Index c : column(0)) expected.push_back(model.dofmap.cell_nodes(c)[0]);
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(nodes, expected);
  // A node set (the corner node) reaches the one cell with that vertex.
  auto c = dg0_plate();
  casefile::NodeSetSpec corner;
  corner.name = "corner";
  corner.lower = corner.upper = Vec3(4.0, 2.0, 0.0);
  c.node_sets = {corner};
  const auto model2 = setup::build_discretization(c);
  EXPECT_EQ(setup::set_dof_nodes(model2, "corner", {}), std::vector<Index>{model2.dofmap.cell_nodes(31)[0]});
}

TEST(DriverBoundaryConditions, DirichletOnAFaceSetMovesDegreeZeroCells) {
  auto c = dg0_plate();
  c.dirichlet = {fixed("xmin", 0), fixed("xmin", 1), fixed("xmax", 0, 0.01)};
  const auto model = setup::build_discretization(c);
  const auto bc = setup::build_dirichlet(model);
  EXPECT_EQ(bc.dofs.size(), 4u * 2 + 4u);
  const auto dir = (std::filesystem::temp_directory_path() / "perimorph_bc_dg0").string();
  const auto run = run::run_static(model, {dir, true});
  ASSERT_EQ(run.reactions.size(), 2u);
  EXPECT_GT(run.strain_energy, 0.0);
  EXPECT_GT(run.reactions[1].x(), 0.0);  // xmax pulled in +x
  EXPECT_NEAR(run.reactions[0].x(), -run.reactions[1].x(), 1e-9 * run.reactions[1].x());
  // Interior columns moved between 0 and 0.01.
  const double u = run.displacement[static_cast<std::size_t>(model.dofmap.cell_nodes(3)[0] * 2)];
  EXPECT_GT(u, 0.0);
  EXPECT_LT(u, 0.01);
}

TEST(DriverBoundaryConditions, TractionAndBodyForceOnDegreeZeroCellsAddUp) {
  auto c = dg0_plate();
  casefile::TractionSpec t;
  t.set = "xmax";
  t.value = Vec3(3.0, -1.0, 0.0);
  c.tractions = {t};
  c.loading.body_force = Vec3(0.0, 2.0, 0.0);
  const auto model = setup::build_discretization(c);
  const auto F = setup::build_external_force(model);
  // Traction: 3 x (face length 2 x thickness 0.5) on the last column's nodes;
  // body force: 2 x (area 8 x thickness 0.5) spread over every cell.
  double fx = 0.0, fy = 0.0, fx_last = 0.0;
  for (Index n = 0; n < model.dofmap.num_nodes(); ++n) {
    fx += F[static_cast<std::size_t>(2 * n)];
    fy += F[static_cast<std::size_t>(2 * n + 1)];
  }
  for (Index cell : column(7)) fx_last += F[static_cast<std::size_t>(2 * model.dofmap.cell_nodes(cell)[0])];
  EXPECT_NEAR(fx, 3.0, 1e-12);
  EXPECT_NEAR(fx_last, 3.0, 1e-12);
  EXPECT_NEAR(fy, -1.0 + 8.0, 1e-12);
  // Each cell takes its own volume's body force: 2 x 0.25 x 0.5, plus the traction on the last column.
  for (Index cell : column(3))
    EXPECT_NEAR(F[static_cast<std::size_t>(2 * model.dofmap.cell_nodes(cell)[0] + 1)], 0.25, 1e-12);
}

TEST(DriverBoundaryConditions, HybridFaceSetReachesVertexAndCentroidNodes) {
  // α = 1 on x ≥ 2 (purely non-local there, DG0), local on the left: `ymax`
  // reaches the CG nodes of the left part and the DG0 cells of the right part.
  auto c = dg0_plate();
  c.alpha.value = 0.0;
  casefile::AlphaRegionSpec r;
  r.shape = casefile::AlphaShapeKind::box;
  r.lower = Vec3(2.0, -1.0, 0.0);
  r.upper = Vec3(5.0, 3.0, 0.0);
  c.alpha.regions = {r};
  const auto model = setup::build_discretization(c);
  const auto nodes = setup::set_dof_nodes(model, "ymax", {});
  Index centroids = 0, vertices = 0;
  for (Index n : nodes) (model.dofmap.mesh_node(n) < 0 ? centroids : vertices) += 1;
  Index dg0_top = 0;
  for (Index cell = 24; cell < 32; ++cell)
    dg0_top += model.dofmap.continuity(cell) == dofs::Continuity::discontinuous_constant ? 1 : 0;
  ASSERT_GT(dg0_top, 0);
  EXPECT_EQ(centroids, dg0_top);
  EXPECT_GT(vertices, 0);
}

TEST(DriverBoundaryConditions, UnknownOrEmptySetIsAnErrorWithItsLocation) {
  auto c = dg0_plate();
  auto bc = fixed("ymx", 1);
  bc.where = {"plate.toml", 12, 1, "dirichlet[1]"};
  c.dirichlet = {bc};
  const auto model = setup::build_discretization(c);
  try {
    (void)setup::build_dirichlet(model);
    FAIL() << "expected an unknown set to be reported";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind("plate.toml:12:1: key 'dirichlet[1]': the mesh has no set named 'ymx'", 0), 0u)
        << msg;
    EXPECT_NE(msg.find("did you mean 'ymax'?"), std::string::npos) << msg;
  }
  auto m2 = setup::build_discretization(dg0_plate());
  m2.mesh.node_sets["nothing"] = {};
  try {
    (void)setup::set_dof_nodes(m2, "nothing", {"plate.toml", 3, 1, "dirichlet[2]"});
    FAIL() << "expected a set that reaches no dof to be reported";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("set 'nothing' reaches no degree of freedom"), std::string::npos)
        << e.what();
  }
  // A traction on a node set, or on a misspelt face set.
  auto c3 = dg0_plate();
  casefile::TractionSpec t;
  t.set = "xmaxx";
  c3.tractions = {t};
  try {
    (void)setup::build_external_force(setup::build_discretization(c3));
    FAIL() << "expected a misspelt face set to be reported";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean 'xmax'?"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace perimorph
