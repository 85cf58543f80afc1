// Local damage in a run (THEORY §6; evolution/local_damage.hpp): the law
// against its closed form through the whole pipeline, d = 0 reproducing
// elasticity bit for bit, the energy ledger W = U + D_damage + D_fracture +
// overshoot + released (released ≥ 0, and what the finite load steps cost
// vanishing as they shrink), the handover (α only where d = d_c; bonds fail
// only where d = d_c), and 1 and 2 threads giving the same run.

#include "perimorph/evolution/bond_failure.hpp"
#include "perimorph/evolution/local_damage.hpp"
#include "perimorph/run/static_run.hpp"
#include "perimorph/setup/boundary_conditions.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/system/stiffness.hpp"
#include "support/fracture_cases.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace perimorph {
namespace {

using testing::read_rows;

std::string scratch_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("perimorph_damage_" + name);
  std::filesystem::remove_all(dir);
  return dir.string();
}

casefile::DamageSpec damage(double k0, double k1, double d_c) {
  casefile::DamageSpec d;
  d.enabled = true;
  d.k0 = k0;
  d.k1 = k1;
  d.d_c = d_c;
  return d;
}

/// A bar [0, 10] of 20 cells, E = 1000, area 1, pulled at x = 10 to u = 0.15 λ
/// (ε = 0.015 λ); damage onset at ε = 0.01.
casefile::CaseConfig damaged_bar(std::vector<double> factors) {
  auto c = testing::box_case(1, {20, 1, 1}, Vec3(10.0, 0, 0), 1000.0, 0.0);
  c.materials[0].damage = damage(0.05, 1.0, 0.8);
  c.dirichlet = {testing::fixed("xmin", 0), testing::fixed("xmax", 0, 0.15)};
  c.loading.factors = std::move(factors);
  c.solver.rtol = 1e-12;
  return c;
}

TEST(LocalDamageRun, HomogeneousBarFollowsTheClosedFormLoadingUnloadingReloading) {
  const std::vector<double> factors{0.5, 1.0, 1.5, 1.0, 0.5, 1.2, 2.0, 3.0, 2.0};
  const auto run =
      run::run_static(setup::build_discretization(damaged_bar(factors)), {scratch_dir("bar"), true});
  ASSERT_EQ(run.history.size(), factors.size());
  const auto it = std::find(run.reaction_names.begin(), run.reaction_names.end(), "xmax");
  ASSERT_NE(it, run.reaction_names.end());
  const auto k = static_cast<std::size_t>(it - run.reaction_names.begin());
  double Ymax = 0.0, d_prev = 0.0;
  for (std::size_t i = 0; i < factors.size(); ++i) {
    const double eps = 0.015 * factors[i];
    Ymax = std::max(Ymax, 0.5 * 1000.0 * eps * eps);
    const double d = std::clamp((Ymax - 0.05) / 1.0, 0.0, 0.8);
    EXPECT_NEAR(run.history[i].reactions[k].x(), (1.0 - d) * 1000.0 * eps, 1e-9 * 1000.0 * eps)
        << "increment " << i + 1 << ", d = " << d;
    // (The iterative solve, rtol 1e-12, gives the strain to ~1e-11; d = (Y − k0)/k1
    // magnifies that by 2Y/(k1 d) ≲ 10 here.)
    EXPECT_NEAR(run.history[i].max_damage, d, 1e-9);
    EXPECT_GE(run.history[i].max_damage, d_prev) << "d never decreases";
    d_prev = run.history[i].max_damage;
    // Homogeneous and displacement-controlled: one update settles the increment.
    EXPECT_LE(run.history[i].damage_iterations, 1);
    // D = (k0 d + ½ k1 d²) × volume 10, exactly (the threshold on the path).
    EXPECT_NEAR(run.history[i].damage_dissipated, (0.05 * d + 0.5 * d * d) * 10.0, 1e-9);
  }
  EXPECT_EQ(run.history.back().max_damage, 0.8) << "capped at d_c, exactly";
  EXPECT_EQ(run.history.back().critical_points, 20u * 2u) << "every point at d_c";
}

/// A plate 4 × 2 (16 × 8 cells) pulled along x to ε̄ = 1e-3 λ, plane strain.
/// `weak`: a band 1 wide across the middle whose threshold k0 is half.
casefile::CaseConfig damaged_plate(double k0, int increments, double final_factor, bool weak) {
  auto c = testing::box_case(2, {16, 8, 1}, Vec3(4.0, 2.0, 1.0), 1.0, 0.25);
  c.materials[0].damage = damage(k0, 5e-6, 0.9);  // hardening to λ = 1.5 (no snap-back)
  if (weak) {
    casefile::RegionSpec r;
    r.name = "band";
    r.id = 1;
    r.lower = Vec3(1.5, -1.0, 0.0);
    r.upper = Vec3(2.5, 3.0, 0.0);
    c.regions = {r};
    auto m = c.materials[0];
    m.name = "weak";
    m.region = "band";
    m.damage.k0 = 0.5 * k0;
    c.materials.push_back(m);
  }
  casefile::NodeSetSpec corner;
  corner.name = "origin";
  c.node_sets = {corner};
  c.dirichlet = {testing::fixed("xmin", 0), testing::fixed("xmax", 0, 0.004), testing::fixed("origin", 1)};
  c.loading.factors.clear();
  for (int i = 1; i <= increments; ++i) c.loading.factors.push_back(final_factor * i / increments);
  c.solver.rtol = 1e-12;
  return c;
}

TEST(LocalDamageRun, BelowTheThresholdTheRunIsTheElasticRunBitForBit) {
  auto elastic = damaged_plate(1.0, 4, 1.0, false);
  elastic.materials[0].damage = {};
  const auto a = run::run_static(setup::build_discretization(elastic), {scratch_dir("elastic"), true});
  const auto b = run::run_static(setup::build_discretization(damaged_plate(1.0, 4, 1.0, false)),
                                 {scratch_dir("undamaged"), true});
  ASSERT_EQ(a.displacement.size(), b.displacement.size());
  for (std::size_t k = 0; k < a.displacement.size(); ++k) ASSERT_EQ(a.displacement[k], b.displacement[k]);
  for (std::size_t i = 0; i < a.history.size(); ++i) {
    EXPECT_EQ(a.history[i].strain_energy, b.history[i].strain_energy);
    EXPECT_EQ(a.history[i].external_work, b.history[i].external_work);
    EXPECT_EQ(b.history[i].max_damage, 0.0);
  }
}

TEST(LocalDamageRun, EnergyLedgerBalancesAndTheStepCostVanishesWithTheStep) {
  // Y far from the band ≈ ½ E ε̄² (plane strain, 1.07) ≈ 6e-7 at λ = 1: the
  // band (k0 = 1.5e-7) damages first, then the rest (k0 = 3e-7).
  auto lost = [](int increments) {
    const auto run = run::run_static(setup::build_discretization(damaged_plate(3e-7, increments, 1.5, true)),
                                     {scratch_dir("ledger"), true});
    for (const auto& r : run.history) {
      const double W = r.external_work;
      EXPECT_GE(r.released, -1e-9 * W) << "increment " << r.increment << " of " << increments;
      EXPECT_NEAR(W, r.strain_energy + r.damage_dissipated + r.overshoot + r.released, 1e-12 * W);
      EXPECT_GE(r.overshoot, 0.0);
    }
    const auto& last = run.history.back();
    EXPECT_GT(last.damage_dissipated, 0.05 * last.external_work) << "the damage dissipates";
    return (last.overshoot + last.released) / last.external_work;
  };
  const double coarse = lost(6), fine = lost(24);
  EXPECT_GT(coarse, 0.0);
  // First order in the load step (measured: 0.0247, 0.0125, 0.0062, 0.0031,
  // 0.0016 of W for 6, 12, 24, 48, 96 increments): a quarter, with slack.
  EXPECT_LT(fine, 0.3 * coarse) << "coarse " << coarse << ", fine " << fine;
}

TEST(LocalDamageRun, NewtonIsTheStepIndependentLimitOfTheFixedPointWithFewerUpdates) {
  // The weak-band plate, damage spreading from the band, solved by the fixed
  // point and by Newton ([damage] solver = "newton") in 12 and 48 increments.
  // Newton's increment is d = max(d_n, (Y(u) − k0)/k1) at every point; the
  // fixed point keeps the largest d a point reached during its iterations, and
  // while the band localizes some points unload, so it spreads more damage,
  // by an amount first order in the step (measured, final D: secant 1.1227e-6,
  // 1.1129e-6, 1.1086e-6 for 12, 48, 192 increments, Newton 1.10676e-6 for all
  // three; updates 95, 307, 1062 against 8, 32, 125).
  struct Result {
    double D, U;
    int updates;
  };
  auto run_with = [](casefile::DamageSolver solver, int increments) {
    auto c = damaged_plate(3e-7, increments, 1.5, true);
    c.damage.solver = solver;
    c.damage.tolerance = 1e-8;
    c.solver.petsc_options = "-ksp_type preonly -pc_type cholesky";
    const auto run = run::run_static(setup::build_discretization(c), {scratch_dir("newton"), true});
    Result r{run.history.back().damage_dissipated, run.history.back().strain_energy, 0};
    for (const auto& h : run.history) {
      r.updates += h.damage_iterations;
      // The ledger holds along either path.
      EXPECT_GE(h.released, -1e-9 * h.external_work) << "increment " << h.increment;
      EXPECT_NEAR(h.external_work, h.strain_energy + h.damage_dissipated + h.overshoot + h.released,
                  1e-12 * h.external_work);
    }
    return r;
  };
  const Result s12 = run_with(casefile::DamageSolver::secant, 12);
  const Result s48 = run_with(casefile::DamageSolver::secant, 48);
  const Result n12 = run_with(casefile::DamageSolver::newton, 12);
  const Result n48 = run_with(casefile::DamageSolver::newton, 48);
  EXPECT_GT(n12.D, 0.0);
  EXPECT_NEAR(n48.D, n12.D, 1e-6 * n12.D) << "Newton: the same state whatever the step";
  EXPECT_NEAR(n48.U, n12.U, 1e-6 * n12.U);
  EXPECT_GT(s12.D, n12.D);
  EXPECT_LT(s48.D - n12.D, 0.5 * (s12.D - n12.D))
      << "the fixed point approaches Newton's state with the step";
  EXPECT_LT(n12.updates, s12.updates / 4) << "secant " << s12.updates << ", newton " << n12.updates;
  EXPECT_LT(n48.updates, s48.updates / 4) << "secant " << s48.updates << ", newton " << n48.updates;
}

TEST(LocalDamageRun, HandoverInsertsAlphaOnlyWhereTheDamageIsCriticalAndBreaksBondsOnlyThere) {
  const auto c = testing::handover_plate(8);
  const setup::Discretization disc = setup::build_discretization(c);
  const std::string dir = scratch_dir("handover");
  const auto run = run::run_static(disc, {dir, true});
  const auto rows = read_rows(dir + "/test.csv");
  ASSERT_EQ(rows.size(), 8u);
  bool critical_seen = false;
  for (const auto& r : rows) {
    if (r.at("critical_points") == 0.0) {
      EXPECT_EQ(r.at("alpha_balls"), 0.0) << "α grew before any point reached d_c";
      EXPECT_EQ(r.at("bonds_broken"), 0.0) << "a bond failed before any point reached d_c";
    }
    critical_seen = critical_seen || r.at("critical_points") > 0.0;
  }
  ASSERT_TRUE(critical_seen) << "the case must reach d_c";
  ASSERT_GT(rows.back().at("bonds_broken"), 0.0) << "the case must break bonds";
  // Every ball sits on a cell that is critical at the end (d never decreases),
  // and every critical cell is inside α = 1.
  const auto& dm = *disc.damage;
  const int npts = dm.points_per_cell;
  auto critical_cell = [&](Index cell) {
    for (int q = 0; q < npts; ++q)
      if (setup::DamageModel::at(run.damage, cell, q, npts) >= 0.2) return true;
    return false;
  };
  const auto balls = read_rows(dir + "/test_alpha.csv");
  ASSERT_FALSE(balls.empty());
  for (const auto& b : balls) {
    const auto cell = static_cast<Index>(b.at("cell"));
    EXPECT_TRUE(critical_cell(cell)) << "a ball on cell " << cell << ", which is not critical";
  }
  for (Index cell = 0; cell < disc.mesh.num_cells(); ++cell) {
    if (!critical_cell(cell)) continue;
    for (Index n : disc.mesh.cell(cell)) EXPECT_EQ(run.alpha(disc.mesh.node(n)), 1.0) << "cell " << cell;
  }
  // Every failed bond has both ends at d = d_c: its ends lie in critical cells.
  const auto bonds = read_rows(dir + "/test_failed_bonds.csv");
  ASSERT_FALSE(bonds.empty());
  auto cell_of = [&](double x, double y) {
    for (Index cell = 0; cell < disc.mesh.num_cells(); ++cell) {
      const auto [lo, hi] = std::pair{disc.mesh.node(disc.mesh.cell(cell).front()),
                                      disc.mesh.node(disc.mesh.cell(cell).back())};
      if (x >= lo.x() && x <= hi.x() && y >= lo.y() && y <= hi.y()) return cell;
    }
    return Index{-1};
  };
  for (const auto& b : bonds) {
    EXPECT_TRUE(critical_cell(cell_of(b.at("xg"), b.at("yg"))));
    EXPECT_TRUE(critical_cell(cell_of(b.at("xh"), b.at("yh"))));
  }
}

TEST(LocalDamageRun, OneAndTwoThreadsGiveTheSameRun) {
  // The first six increments of the handover plate: damage, d_c reached, α
  // grown and the model rebuilt (the crack runs at the seventh; the bond
  // failure loop's thread independence is tested in fracture_test.cpp).
  auto c = testing::handover_plate(8);
  c.loading.factors.resize(6);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const auto one = run::run_static(setup::build_discretization(c), {scratch_dir("t1"), true});
  omp_set_num_threads(2);
  const auto two = run::run_static(setup::build_discretization(c), {scratch_dir("t2"), true});
  omp_set_num_threads(threads);
  ASSERT_EQ(one.displacement.size(), two.displacement.size());
  for (std::size_t k = 0; k < one.displacement.size(); ++k)
    ASSERT_EQ(one.displacement[k], two.displacement[k]);
  ASSERT_EQ(one.damage, two.damage);
  ASSERT_GT(one.history.back().alpha_balls, 0u);
  ASSERT_EQ(one.failed_bond_points.size(), two.failed_bond_points.size());
  for (std::size_t i = 0; i < one.history.size(); ++i) {
    EXPECT_EQ(one.history[i].damage_dissipated, two.history[i].damage_dissipated);
    EXPECT_EQ(one.history[i].dissipated, two.history[i].dissipated);
    EXPECT_EQ(one.history[i].damage_iterations, two.history[i].damage_iterations);
  }
}

TEST(LocalDamageComponent, BondsFailOnlyBetweenPointsAtCriticalDamage) {
  auto c = testing::pulled_case(2, {1.0}, 1e-3);
  c.materials[0].damage = damage(1.0, 1.0, 0.2);
  const setup::Discretization disc = setup::build_discretization(c);
  evolution::RunState state(disc);
  // A kink across x = 2.03: the bonds across it stretch most.
  for (Index a = 0; a < disc.dofmap.num_nodes(); ++a) {
    const Vec3 x = disc.dofmap.node_coordinate(disc.mesh, a);
    state.u[static_cast<std::size_t>(a * 2)] = 0.5e-3 * x.x() + (x.x() > 2.03 ? 2e-3 : 0.0);
  }
  evolution::BondFailure failure(disc);
  EXPECT_TRUE(failure.select(state).empty()) << "no point at d_c: no bond may fail";
  // Critical on the right of x = 2 only.
  const int npts = disc.damage->points_per_cell;
  std::vector<char> critical(static_cast<std::size_t>(disc.mesh.num_cells()), 0);
  for (Index cell = 0; cell < disc.mesh.num_cells(); ++cell)
    if (disc.mesh.cell_centroid(cell).x() > 2.0) {
      critical[static_cast<std::size_t>(cell)] = 1;
      for (int q = 0; q < npts; ++q) state.history[static_cast<std::size_t>(cell * npts + q)] = 0.2;
    }
  const auto some = failure.select(state);
  ASSERT_FALSE(some.empty());
  for (const auto& b : some) {
    EXPECT_TRUE(critical[static_cast<std::size_t>(b.id.e)]);
    EXPECT_TRUE(critical[static_cast<std::size_t>(b.id.f)]);
  }
  std::fill(state.history.begin(), state.history.end(), 0.2);
  EXPECT_GT(failure.select(state).size(), some.size()) << "all critical: the bonds across the kink fail";
}

}  // namespace
}  // namespace perimorph
