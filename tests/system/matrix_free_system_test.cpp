// The matrix-free constrained system ([solver] operator = "matrix-free",
// system/matrix_free_stiffness.hpp, issue 16 item 3) against the assembled
// one on the same structured DG0 grid with α ≡ 1: the same K x, the same
// right-hand side, the same solution to the solver's tolerance and the same
// run (reactions, energies); 2D and 3D, both horizon edges, non-cubic cells,
// prescribed values, tractions and a body force. Cases it does not cover are
// refused naming the key and the reason.

#include "perimorph/casefile/parse_case.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/run/static_run.hpp"
#include "perimorph/setup/boundary_conditions.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/system/constrained_system.hpp"
#include "perimorph/system/stiffness.hpp"
#include "support/cases.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <string>

namespace perimorph {
namespace {

using testing::fixed;

/// A grid of DG0 cells with α ≡ 1 (pmb kernel), fixed at x = 0, pulled at
/// x = L by a prescribed u_x and a traction on its top face, under a body force.
casefile::CaseConfig grid(int dim, casefile::HorizonEdge edge, Vec3 spacing, casefile::SolverOperator op) {
  const std::array<Index, 3> cells =
      dim == 2 ? std::array<Index, 3>{10, 7, 1} : std::array<Index, 3>{8, 6, 5};
  Vec3 extent = Vec3::Ones();
  for (int d = 0; d < dim; ++d)
    extent[d] = spacing[d] * static_cast<double>(cells[static_cast<std::size_t>(d)]);
  auto c = testing::box_case(dim, cells, extent, 200.0, 0.25);
  testing::add_nonlocal(c, casefile::KernelKind::pmb, 2.6 * spacing.head(dim).maxCoeff(), 0.0, 1,
                        casefile::Discretization::discontinuous_constant);
  c.nonlocal.horizon_edge = edge;
  c.alpha.value = 1.0;
  c.dirichlet = {fixed("xmin", 0), fixed("xmin", 1), fixed("xmax", 0, 0.01 * extent.x())};
  if (dim == 3) c.dirichlet.push_back(fixed("xmin", 2));
  casefile::TractionSpec t;
  t.set = "ymax";
  t.value = Vec3(0.3, 0.5, 0.0);
  c.tractions = {t};
  c.loading.body_force = Vec3(0.0, -0.2, dim == 3 ? 0.1 : 0.0);
  c.loading.factors = {0.5, 1.0};
  c.solver.rtol = 1e-12;
  c.solver.op = op;
  return c;
}

/// Every solver option the tests rely on (in one gtest process, earlier tests
/// leave theirs in PETSc's options database, and a case's options do not
/// replace those already there).
void use_cg_and_gamg() {
  la::set_option("-ksp_type", "cg");
  la::set_option("-pc_type", "gamg");
}

double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

double max_diff(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) m = std::max(m, std::abs(a[k] - b[k]));
  return m;
}

struct Variant {
  int dim;
  casefile::HorizonEdge edge;
  Vec3 spacing;
};

class MatrixFreeSystem : public ::testing::TestWithParam<Variant> {};

TEST_P(MatrixFreeSystem, ProductRightHandSideAndSolutionEqualTheAssembledOnes) {
  const Variant v = GetParam();
  const auto da =
      setup::build_discretization(grid(v.dim, v.edge, v.spacing, casefile::SolverOperator::assembled));
  const auto dm =
      setup::build_discretization(grid(v.dim, v.edge, v.spacing, casefile::SolverOperator::matrix_free));
  ASSERT_EQ(da.dofmap.num_dofs(), dm.dofmap.num_dofs());
  // The matrix-free discretization assembles no bond: its graph is the diagonal one.
  EXPECT_EQ(dm.nonlocal->graph.num_pairs(), static_cast<std::size_t>(dm.mesh.num_cells()));
  system::ConstrainedSystem assembled(da, system::assemble_stiffness(da).K, setup::build_dirichlet(da),
                                      setup::build_external_force(da));
  system::ConstrainedSystem free(dm, system::build_matrix_free_stiffness(dm), setup::build_dirichlet(dm),
                                 setup::build_external_force(dm));
  ASSERT_TRUE(free.matrix_free());
  ASSERT_FALSE(assembled.matrix_free());
  const Index n = da.dofmap.num_dofs();
  // K x for a field with every dof non-zero.
  std::vector<double> xv(static_cast<std::size_t>(n));
  for (std::size_t k = 0; k < xv.size(); ++k) xv[k] = std::sin(0.7 * static_cast<double>(k) + 0.3);
  la::Vector x(n, v.dim), ya(n, v.dim), ym(n, v.dim);
  x.assign(xv);
  assembled.apply_K(x, ya);
  free.apply_K(x, ym);
  const auto Ka = ya.to_std(), Km = ym.to_std();
  EXPECT_LE(max_diff(Ka, Km), 1e-12 * max_abs(Ka));
  const auto ra = assembled.rhs_unit().to_std(), rm = free.rhs_unit().to_std();
  EXPECT_LE(max_diff(ra, rm), 1e-12 * max_abs(ra));
  use_cg_and_gamg();
  assembled.attach_solver();
  free.attach_solver();
  la::Vector ua(n, v.dim), um(n, v.dim);
  assembled.solve(0.7, ua);
  const la::SolveReport rep = free.solve(0.7, um);
  EXPECT_LE(rep.relative_residual, 1e-11);
  const auto sa = ua.to_std(), sm = um.to_std();
  EXPECT_LE(max_diff(sa, sm), 1e-9 * max_abs(sa));
  // The prescribed dofs at their values (to round-off: the AMG's coarse
  // levels mix them with free dofs).
  for (std::size_t k = 0; k < free.bc().dofs.size(); ++k)
    EXPECT_NEAR(sm[static_cast<std::size_t>(free.bc().dofs[k])], 0.7 * free.bc().values[k],
                1e-12 * max_abs(sa));
}

INSTANTIATE_TEST_SUITE_P(
    Grids, MatrixFreeSystem,
    ::testing::Values(Variant{3, casefile::HorizonEdge::cutoff, Vec3(1.0, 1.0, 1.0)},
                      Variant{3, casefile::HorizonEdge::partial_volume, Vec3(1.0, 0.8, 1.2)},
                      Variant{2, casefile::HorizonEdge::cutoff, Vec3(0.5, 0.5, 1.0)},
                      Variant{2, casefile::HorizonEdge::partial_volume, Vec3(0.5, 0.4, 1.0)}));

TEST(MatrixFreeRun, GivesTheAssembledRunsReactionsAndEnergies) {
  const auto scratch = std::filesystem::temp_directory_path() / "perimorph_matrix_free_run";
  use_cg_and_gamg();
  auto run = [&](casefile::SolverOperator op, const char* name) {
    const auto d = setup::build_discretization(grid(3, casefile::HorizonEdge::cutoff, Vec3::Ones(), op));
    return run::run_static(d, {(scratch / name).string(), true});
  };
  const auto a = run(casefile::SolverOperator::assembled, "assembled");
  const auto m = run(casefile::SolverOperator::matrix_free, "matrix_free");
  ASSERT_EQ(a.history.size(), 2U);
  ASSERT_EQ(m.history.size(), 2U);
  for (std::size_t i = 0; i < 2; ++i) {
    const auto &ra = a.history[i], &rm = m.history[i];
    EXPECT_NEAR(rm.strain_energy, ra.strain_energy, 1e-9 * ra.strain_energy);
    EXPECT_NEAR(rm.external_work, ra.external_work, 1e-9 * ra.external_work);
    for (std::size_t s = 0; s < ra.reactions.size(); ++s)
      EXPECT_LE((rm.reactions[s] - ra.reactions[s]).norm(), 1e-8 * ra.reactions[s].norm());
  }
  EXPECT_LE(max_diff(a.displacement, m.displacement), 1e-9 * max_abs(a.displacement));
  std::filesystem::remove_all(scratch);
}

/// The message of check_matrix_free for the matrix-free grid changed by `edit`.
template <class Edit>
std::string refusal(Edit edit) {
  auto c = grid(3, casefile::HorizonEdge::cutoff, Vec3::Ones(), casefile::SolverOperator::matrix_free);
  edit(c);
  try {
    setup::check_matrix_free(c);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(MatrixFreeCase, CasesItDoesNotCoverAreRefusedWithTheReason) {
  EXPECT_EQ(refusal([](casefile::CaseConfig&) {}), "");
  const std::pair<std::string, std::function<void(casefile::CaseConfig&)>> cases[] = {
      {"[alpha] value is 0.5", [](casefile::CaseConfig& c) { c.alpha.value = 0.5; }},
      {"discretization is not \"discontinuous-constant\"",
       [](casefile::CaseConfig& c) { c.nonlocal.discretization = casefile::Discretization::discontinuous; }},
      {"quadrature is 2", [](casefile::CaseConfig& c) { c.nonlocal.quadrature = 2; }},
      {"the case has [fracture]", [](casefile::CaseConfig& c) { c.fracture.enabled = true; }},
      {"the case has [adaptivity]", [](casefile::CaseConfig& c) { c.adaptivity.enabled = true; }},
      {"the mesh has a hole", [](casefile::CaseConfig& c) { c.mesh.holes.emplace_back(); }},
      {"the mesh has a pre-crack cut", [](casefile::CaseConfig& c) { c.mesh.cuts.emplace_back(); }},
      {"the mesh is not a box", [](casefile::CaseConfig& c) { c.mesh.kind = casefile::MeshKind::gmsh; }},
      {"there is no [nonlocal] section", [](casefile::CaseConfig& c) { c.nonlocal.enabled = false; }},
  };
  for (const auto& [expected, edit] : cases) {
    const std::string message = refusal(edit);
    EXPECT_NE(message.find("operator = \"matrix-free\" covers"), std::string::npos) << message;
    EXPECT_NE(message.find(expected), std::string::npos) << expected << " not in: " << message;
  }
}

TEST(MatrixFreeCase, TheCaseFileKeysAreReadAndChecked) {
  const std::string head =
      "[mesh]\ndim = 2\nlower = [0, 0]\nupper = [1, 1]\ncells = [4, 4]\n"
      "[[material]]\nname = \"m\"\nE = 1.0\nnu = 0.25\n[solver]\n";
  const auto c = casefile::parse_case_string(
      head + "operator = \"matrix-free\"\npreconditioner_horizon = 2.0\n", "mf.toml");
  EXPECT_EQ(c.solver.op, casefile::SolverOperator::matrix_free);
  EXPECT_EQ(c.solver.preconditioner_horizon, 2.0);
  EXPECT_EQ(casefile::parse_case_string(head, "mf.toml").solver.op, casefile::SolverOperator::assembled);
  auto message = [&](const std::string& tail) -> std::string {
    try {
      casefile::parse_case_string(head + tail, "mf.toml");
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  const std::string misspelt = message("operator = \"matrixfree\"\n");
  EXPECT_NE(misspelt.find("mf.toml:11"), std::string::npos) << misspelt;
  EXPECT_NE(misspelt.find("did you mean \"matrix-free\""), std::string::npos) << misspelt;
  const std::string without = message("preconditioner_horizon = 2.0\n");
  EXPECT_NE(without.find("needs operator = \"matrix-free\""), std::string::npos) << without;
  const std::string narrow = message("operator = \"matrix-free\"\npreconditioner_horizon = 0.5\n");
  EXPECT_NE(narrow.find("must lie in [1, 10]"), std::string::npos) << narrow;
}

}  // namespace
}  // namespace perimorph
