// Parts cut free by bond failure (floating_parts.hpp): a plate cut through
// by failed bonds leaves its right half held only along x; the failure update
// finds that part, holds its free mode by a minimal support, the matrix stays
// non-singular and the support carries no force (the half moves rigidly with
// its pulled edge). A cut-free part with an unbalanced applied force is an
// error, and so is a force on a node that failures left without stiffness,
// and a force doing work on a motion inside a cell.

#include "perimorph/evolution/floating_parts.hpp"
#include "perimorph/assembly/bond_stretch.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/evolution/bond_failure.hpp"
#include "perimorph/evolution/part_support.hpp"
#include "perimorph/partition/partition.hpp"
#include "perimorph/run/static_run.hpp"
#include "perimorph/setup/boundary_conditions.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/system/stiffness.hpp"
#include "support/cases.hpp"
#include "support/floating_plate.hpp"

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include <algorithm>
#include <filesystem>
#include <set>

namespace perimorph {
namespace {

using testing::break_and_support;
using testing::constrained_system;
using testing::jump_at_middle;

/// Assembles, constrains and fails every bond across x = 2.
system::ConstrainedSystem cut_plate(const setup::Discretization& model, evolution::RunState& state) {
  system::ConstrainedSystem out = constrained_system(model);
  state.u = jump_at_middle(model);
  EXPECT_GT(break_and_support(model, state, out), 100u);
  return out;
}

TEST(FloatingParts, CutFreeHalfIsHeldWithoutForce) {
  const auto model = setup::build_discretization(testing::floating_plate(false));
  evolution::RunState state(model);
  system::ConstrainedSystem cut = cut_plate(model, state);
  // Every bond across x = 2 failed: no cell pair across it keeps one.
  const auto sp = evolution::BondFailure(model).space(state);
  for (const auto& [e, f] : assembly::bonded_pairs(sp)) {
    const auto ce = model.mesh.cell_centroid(e), cf = model.mesh.cell_centroid(f);
    EXPECT_FALSE((ce.x() < 2.0) != (cf.x() < 2.0)) << "cells " << e << ", " << f << " still bonded";
  }
  // The right half is held along x only (its pulled edge): one part, free in y.
  EXPECT_EQ(state.floating_parts, 1u);
  const Eigen::MatrixXd A = cut.A().to_dense();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(A, Eigen::EigenvaluesOnly);
  const double ratio = eig.eigenvalues().minCoeff() / eig.eigenvalues().maxCoeff();
  std::printf("cut plate: %zu floating part(s), eigenvalue ratio of A %.3e\n", state.floating_parts, ratio);
  EXPECT_GT(ratio, 1e-12);
  // Solution: the left half at rest, the right half moved rigidly by 0.004
  // along x. A support with a force on it would bend or shift the half.
  const std::vector<double> rhs = cut.rhs_unit().to_std();
  const Eigen::VectorXd u = A.ldlt().solve(Eigen::Map<const Eigen::VectorXd>(rhs.data(), A.rows()));
  const auto& dm = model.dofmap;
  double err = 0.0;
  for (Index c = 0; c < model.mesh.num_cells(); ++c) {
    const double ux = model.mesh.cell_centroid(c).x() > 2.0 ? 0.004 : 0.0;
    for (Index a : dm.cell_nodes(c)) {
      err = std::max(err, std::abs(u[a * 2] - ux));
      err = std::max(err, std::abs(u[a * 2 + 1]));
    }
  }
  std::printf("largest deviation from the rigid motions: %.3e (of 0.004)\n", err);
  EXPECT_LT(err, 1e-10 * 0.004);
}

// The links of the parts of a partition (what each process finds from its
// cells' graph rows, issue 17), gathered in any order, make the whole graph's
// parts: the same floating part and the same pins, bit for bit.
TEST(FloatingParts, LinksOfThePartsFindTheWholeGraphsParts) {
  const auto model = setup::build_discretization(testing::floating_plate(false));
  evolution::RunState state(model);
  system::ConstrainedSystem cut = constrained_system(model);
  state.u = jump_at_middle(model);
  evolution::BondFailure failure(model);
  ASSERT_GT(failure.inspect(state, cut).changes, 100u);
  failure.apply(state, cut);
  const auto sp = failure.space(state);
  std::vector<Index> held(cut.bc().dofs.begin(), cut.bc().dofs.end());
  std::sort(held.begin(), held.end());
  const auto whole_links = evolution::stiffness_links(model, sp);
  const la::DofValuesAt force = [&](std::span<const Index> dofs) { return cut.applied_force_at(dofs); };
  const auto whole = evolution::find_floating_parts(model, whole_links, held, force);
  ASSERT_EQ(whole.parts, 1);
  ASSERT_FALSE(whole.pins.empty());
  auto roots = [](const std::vector<Index>& links) {
    std::set<Index> r;
    for (std::size_t k = 1; k < links.size(); k += 2) r.insert(links[k]);
    return r.size();
  };
  for (int parts : {2, 3, 4}) {
    std::vector<Index> links;
    for (int q = parts - 1; q >= 0; --q) {
      const auto mine = evolution::stiffness_links(model, sp, partition::cells_of_part(model.mesh, parts, q));
      links.insert(links.end(), mine.begin(), mine.end());
    }
    // Alone, the parts' links join less than the whole graph's (on 3 and 4
    // parts; 2 parts split the plate at the cut): the gathering joins them.
    if (parts > 2) {
      EXPECT_GT(roots(links), roots(whole_links)) << parts;
    }
    const auto got = evolution::find_floating_parts(model, links, held, force);
    EXPECT_EQ(got.parts, whole.parts) << parts;
    EXPECT_EQ(got.pins, whole.pins) << parts;
  }
}

TEST(FloatingParts, UnbalancedCutFreePartIsAnError) {
  const auto model = setup::build_discretization(testing::floating_plate(true));
  evolution::RunState state(model);
  try {
    cut_plate(model, state);
    FAIL() << "a part cut free with a traction on it was accepted";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("no quasi-static equilibrium"), std::string::npos) << what;
    EXPECT_NE(what.find("(2, 0, 0) and (4, 2, 0)"), std::string::npos) << what;
  }
}

// Every bond of the last column of cells with a horizontal component fails
// (u_x = (x − 3.75)² there): its nodes keep no stiffness along x while the
// traction pulls them along x. That is an error, not a dropped force.
TEST(FloatingParts, ForceOnANodeLeftWithoutStiffnessIsAnError) {
  auto c = testing::floating_plate(true);
  c.fracture.s_crit = 1e-12;
  const auto model = setup::build_discretization(c);
  system::ConstrainedSystem sys = constrained_system(model);
  evolution::RunState state(model);
  testing::stretch_last_column(model, state.u);
  ASSERT_GT(evolution::BondFailure(model).select(state).size(), 50u);
  try {
    break_and_support(model, state, sys);
    FAIL() << "a node left without stiffness under a force was accepted";
  } catch (const Error& e) {
    const std::string what = e.what();
    std::printf("%s\n", what.c_str());
    EXPECT_NE(what.find("with no stiffness in direction x"), std::string::npos) << what;
    EXPECT_NE(what.find("no quasi-static equilibrium"), std::string::npos) << what;
  }
}

// Pulled by a traction far beyond failure, the plate falls apart: a cell at
// the loaded edge keeps a motion no intact bond resists (cell_mechanisms.hpp)
// that the traction does work on. The run stops with that reason, the
// increment and what was kept (before, CG or Cholesky failed on the singular
// matrix).
TEST(FloatingParts, UnbalancedMechanismStopsTheRunAndSaysWhy) {
  auto c = testing::floating_plate(true);
  c.loading.factors = {0.25, 3.0};  // mean strain 2.5e-4, then 3e-3 > s_crit in most bonds
  c.fracture.s_crit = 1e-3;
  c.solver.petsc_options = "-ksp_type preonly -pc_type cholesky";
  const auto model = setup::build_discretization(c);
  run::RunOptions options;
  options.output_directory = (std::filesystem::temp_directory_path() / "perimorph_floating_plate").string();
  options.quiet = true;
  std::filesystem::remove_all(options.output_directory);
  try {
    run::run_static(model, options);
    FAIL() << "the plate fell apart under a force and the run went on";
  } catch (const Error& e) {
    const std::string what = e.what();
    std::printf("%s\n", what.c_str());
    EXPECT_NE(what.find("increment 2/2"), std::string::npos) << what;
    EXPECT_NE(what.find("that no intact bond resists"), std::string::npos) << what;
    EXPECT_NE(what.find("no quasi-static equilibrium"), std::string::npos) << what;
    EXPECT_NE(what.find("Results of increments 1..1"), std::string::npos) << what;
  }
}
}  // namespace
}  // namespace perimorph
