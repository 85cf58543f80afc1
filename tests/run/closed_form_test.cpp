// Whole-pipeline checks against closed forms (issue 2, item 8): plane strain
// vs plane stress under uniaxial traction, an orthotropic block in uniaxial
// stress (material axes aligned and rotated), and a pre-cracked plate whose
// crack opens under tension. Cases are built as typed CaseConfig structs, the
// form a parsed case file takes.

#include "perimorph/run/static_run.hpp"
#include "perimorph/setup/discretization.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <numbers>

namespace perimorph {
namespace {

std::string scratch_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("perimorph_test_" + name);
  std::filesystem::remove_all(dir);
  return dir.string();
}

casefile::DirichletSpec roller(const std::string& set, int component) {
  casefile::DirichletSpec d;
  d.set = set;
  d.constrained[static_cast<std::size_t>(component)] = true;
  return d;
}

/// Mean strain over all cells of the last increment.
Eigen::VectorXd mean_strain(const setup::Discretization& model, const std::vector<double>& u) {
  const auto f = assembly::cell_strain_stress(model.local_space(), model.stiffness, u);
  const int nv = fem::voigt_size(model.dim());
  Eigen::VectorXd mean = Eigen::VectorXd::Zero(nv);
  Eigen::VectorXd max_dev = Eigen::VectorXd::Zero(nv);
  for (Index c = 0; c < model.mesh.num_cells(); ++c)
    for (int i = 0; i < nv; ++i)
      mean[i] += f.strain[static_cast<std::size_t>(c * nv + i)] / model.mesh.num_cells();
  for (Index c = 0; c < model.mesh.num_cells(); ++c)
    for (int i = 0; i < nv; ++i)
      EXPECT_NEAR(f.strain[static_cast<std::size_t>(c * nv + i)], mean[i], 1e-12) << "strain is not uniform";
  return mean;
}

casefile::CaseConfig uniaxial_plate(casefile::PlaneMode mode, double traction) {
  casefile::CaseConfig c;
  c.path = "uniaxial.toml";
  c.mesh.box = {2, Vec3::Zero(), Vec3(3.0, 2.0, 0.0), {6, 4, 1}};
  c.model.plane = mode;
  c.model.thickness = 0.5;
  casefile::MaterialSpec m;
  m.name = "steel";
  m.E = 200.0;
  m.nu = 0.3;
  c.materials = {m};
  c.dirichlet = {roller("xmin", 0), roller("ymin", 1)};
  casefile::TractionSpec t;
  t.set = "xmax";
  t.value = Vec3(traction, 0, 0);
  c.tractions = {t};
  c.loading.factors = {0.5, 1.0};
  c.output.vtu = false;
  c.solver.rtol = 1e-13;
  return c;
}

TEST(DriverClosedForm, PlaneStressVersusPlaneStrain) {
  const double T = 0.1, E = 200.0, nu = 0.3;
  for (auto mode : {casefile::PlaneMode::stress, casefile::PlaneMode::strain}) {
    const auto model = setup::build_discretization(uniaxial_plate(mode, T));
    const auto run = run::run_static(model, {scratch_dir("uniaxial"), true});
    const auto eps = mean_strain(model, run.displacement);
    if (mode == casefile::PlaneMode::stress) {
      EXPECT_NEAR(eps[0], T / E, 1e-12);
      EXPECT_NEAR(eps[1], -nu * T / E, 1e-12);
    } else {
      EXPECT_NEAR(eps[0], T * (1 - nu * nu) / E, 1e-12);
      EXPECT_NEAR(eps[1], -nu * (1 + nu) * T / E, 1e-12);
    }
    EXPECT_NEAR(eps[2], 0.0, 1e-12);
    // Reaction on xmin balances the applied force T · height · thickness.
    EXPECT_NEAR(run.reactions[0].x(), -T * 2.0 * 0.5, 1e-10);
    // Linear response under a proportional ramp: external work equals strain energy.
    EXPECT_NEAR(run.external_work, run.strain_energy, 1e-12 * run.strain_energy);
  }
}

casefile::CaseConfig orthotropic_block(const Mat3& axes) {
  casefile::CaseConfig c;
  c.path = "ortho.toml";
  c.mesh.box = {3, Vec3::Zero(), Vec3(2.0, 1.0, 1.5), {4, 2, 3}};
  casefile::MaterialSpec m;
  m.name = "composite";
  m.kind = casefile::MaterialKind::orthotropic;
  m.E1 = 60;
  m.E2 = 90;
  m.E3 = 150;
  m.nu12 = 0.3;
  m.nu13 = 0.1;
  m.nu23 = 0.2;
  m.G12 = 25;
  m.G13 = 20;
  m.G23 = 30;
  m.axes = axes;
  c.materials = {m};
  c.dirichlet = {roller("xmin", 0), roller("ymin", 1), roller("zmin", 2)};
  casefile::TractionSpec t;
  t.set = "xmax";
  t.value = Vec3(0.6, 0, 0);
  c.tractions = {t};
  c.output.vtu = false;
  c.solver.rtol = 1e-13;
  return c;
}

TEST(DriverClosedForm, OrthotropicBlockUniaxialStress) {
  const double T = 0.6;
  {
    const auto model = setup::build_discretization(orthotropic_block(Mat3::Identity()));
    const auto run = run::run_static(model, {scratch_dir("ortho"), true});
    const auto eps = mean_strain(model, run.displacement);
    EXPECT_NEAR(eps[0], T / 60, 1e-12);
    EXPECT_NEAR(eps[1], -0.3 * T / 60, 1e-12);
    EXPECT_NEAR(eps[2], -0.1 * T / 60, 1e-12);
    EXPECT_NEAR(eps.tail(3).norm(), 0.0, 1e-12);
  }
  {
    // Material e1 along mesh y, e2 along mesh −x: loading along x is along e2.
    Mat3 axes;
    axes << 0, -1, 0, 1, 0, 0, 0, 0, 1;
    const auto model = setup::build_discretization(orthotropic_block(axes));
    const auto run = run::run_static(model, {scratch_dir("ortho_rot"), true});
    const auto eps = mean_strain(model, run.displacement);
    EXPECT_NEAR(eps[0], T / 90, 1e-12);
    EXPECT_NEAR(eps[1], -0.3 * T / 60, 1e-12);  // ν21/E2 = ν12/E1
    EXPECT_NEAR(eps[2], -0.2 * T / 90, 1e-12);
  }
}

casefile::CaseConfig tension_plate(bool cracked) {
  casefile::CaseConfig c;
  c.path = "cracked.toml";
  c.mesh.box = {2, Vec3::Zero(), Vec3(8.0, 8.0, 0.0), {16, 16, 1}};
  if (cracked) {
    casefile::CutSpec cut;
    cut.origin = Vec3(0.0, 4.0, 0.0);
    cut.edge1 = Vec3(4.0, 0.0, 0.0);
    c.mesh.cuts = {cut};
  }
  casefile::MaterialSpec m;
  m.name = "glass";
  m.E = 70.0;
  m.nu = 0.22;
  c.materials = {m};
  casefile::DirichletSpec bottom = roller("ymin", 1), top = roller("ymax", 1);
  bottom.constrained[0] = true;
  top.value = Vec3(0.0, 0.01, 0.0);
  c.dirichlet = {bottom, top};
  c.output.vtu = false;
  return c;
}

TEST(DriverClosedForm, PreCrackedPlateOpensUnderTension) {
  const auto intact = setup::build_discretization(tension_plate(false));
  const auto cracked = setup::build_discretization(tension_plate(true));
  // 8 crack-face nodes from x = 0 to x = 3.5 are split; the tip at x = 4 is not.
  EXPECT_EQ(cracked.mesh.num_nodes(), intact.mesh.num_nodes() + 8);
  const auto ri = run::run_static(intact, {scratch_dir("intact"), true});
  const auto rc = run::run_static(cracked, {scratch_dir("cracked"), true});
  // Opening at the crack mouth (x = 0): the two copies of the node move apart.
  const int dim = 2;
  std::vector<Index> mouth;
  for (Index n = 0; n < cracked.dofmap.num_nodes(); ++n)
    if (cracked.dofmap.node_coordinate(cracked.mesh, n).isApprox(Vec3(0.0, 4.0, 0.0))) mouth.push_back(n);
  ASSERT_EQ(mouth.size(), 2u);
  const double opening = std::abs(rc.displacement[static_cast<std::size_t>(mouth[0] * dim + 1)] -
                                  rc.displacement[static_cast<std::size_t>(mouth[1] * dim + 1)]);
  EXPECT_GT(opening, 1e-3);  // a sizeable part of the 0.01 imposed
  // The crack makes the plate more compliant: smaller reaction for the same displacement.
  EXPECT_LT(std::abs(rc.reactions[1].y()), 0.9 * std::abs(ri.reactions[1].y()));
  // The tip and the ligament ahead of it stay connected (one node each).
  for (double x : {4.0, 7.0}) {
    int copies = 0;
    for (Index n = 0; n < cracked.dofmap.num_nodes(); ++n)
      copies += cracked.dofmap.node_coordinate(cracked.mesh, n).isApprox(Vec3(x, 4.0, 0.0)) ? 1 : 0;
    EXPECT_EQ(copies, 1) << "x = " << x;
  }
}

}  // namespace
}  // namespace perimorph
