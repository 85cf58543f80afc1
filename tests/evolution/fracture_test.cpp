// Quasi-static fracture by critical stretch (issue 5, THEORY §5): the
// incremental downdate of K, A and the right-hand side equals a reassembly
// without the failed bonds; a bar and a block start to fail at the load the
// critical stretch predicts; the energy bookkeeping W = U before failure and
// W − U − D ≥ 0 after (D at s_crit); failed bonds never heal; the same bonds
// fail with 1 and 2 threads; the failed-bonds file adds up to the CSV columns.

#include "perimorph/assembly/bond_stretch.hpp"
#include "perimorph/bonds/cell_graph.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/evolution/bond_failure.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/partition/partition.hpp"
#include "perimorph/run/static_run.hpp"
#include "perimorph/setup/boundary_conditions.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/system/stiffness.hpp"
#include "support/cases.hpp"
#include "support/fracture_cases.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace perimorph {
namespace {

using testing::fixed;
using testing::pulled_case;
using testing::read_rows;

std::string scratch_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("perimorph_fracture_" + name);
  std::filesystem::remove_all(dir);
  return dir.string();
}

/// An elastic solve at load factor 1 (nothing fails): its displacement and
/// the largest bond stretch, i.e. the stretch per unit load factor.
struct ElasticState {
  std::vector<double> u;
  double max_stretch = 0.0;
};

ElasticState elastic_state(const casefile::CaseConfig& c) {
  auto elastic = c;
  elastic.loading.factors = {1.0};
  elastic.fracture.s_crit = 1e300;
  const auto model = setup::build_discretization(elastic);
  auto run = run::run_static(model, {scratch_dir("elastic"), true});
  const evolution::BondFailure failure(model);
  const evolution::RunState intact(model);
  ElasticState out;
  for (const auto& b : assembly::bonds_over(failure.space(intact), run.displacement, 0.0))
    out.max_stretch = std::max(out.max_stretch, b.stretch);
  out.u = std::move(run.displacement);
  return out;
}

/// A state of `model` at displacement u, nothing failed.
evolution::RunState state_at(const setup::Discretization& model, const std::vector<double>& u) {
  evolution::RunState state(model);
  state.u = u;
  return state;
}

double max_stretch_per_load(const casefile::CaseConfig& c) {
  return elastic_state(c).max_stretch;
}

TEST(Fracture, IncrementalDowndateEqualsReassembly) {
  // Third setting: fully non-local, failures next to the pulled edge, so that
  // failed bonds reach prescribed dofs and the right-hand side changes.
  struct Setting {
    int dim;
    bool at_edge;
  };
  for (const auto [dim, at_edge] : {Setting{1, false}, Setting{2, false}, Setting{2, true}}) {
    SCOPED_TRACE(::testing::Message() << dim << "D" << (at_edge ? ", at the pulled edge" : ""));
    auto c = pulled_case(dim, {1.0}, 1e-3);
    if (at_edge) {
      c.alpha.regions.clear();
      c.alpha.value = 1.0;
    }
    const auto model = setup::build_discretization(c);
    const Index n = model.dofmap.num_dofs();
    const std::vector<double> no_force(static_cast<std::size_t>(n), 0.0);
    system::ConstrainedSystem system(model, system::assemble_stiffness(model).K,
                                     setup::build_dirichlet(model), no_force);
    const la::Matrix& K = system.K();
    const la::Matrix& A = system.A();
    const la::Vector& rhs = system.rhs_unit();
    const Eigen::MatrixXd K_intact = K.to_dense();
    la::Vector rhs_intact(n, dim);
    rhs_intact.copy_from(rhs);
    // A displacement with a kink in the middle: the bonds across it stretch most.
    std::vector<double> u(static_cast<std::size_t>(n), 0.0);
    for (Index a = 0; a < model.dofmap.num_nodes(); ++a) {
      const Vec3 x = model.dofmap.node_coordinate(model.mesh, a);
      const double middle = at_edge ? 3.93 : dim == 1 ? 10.03 : 2.03;
      u[static_cast<std::size_t>(a * dim)] = 0.5e-3 * x.x() + (x.x() > middle ? 2e-3 : 0.0);
    }
    evolution::BondFailure failure(model);
    evolution::RunState state(model);
    state.u = u;
    const auto bonds = failure.select(state);
    ASSERT_GT(bonds.size(), 10u);
    const evolution::FailureEnergy energy = failure.apply(bonds, state, system);
    EXPECT_EQ(state.failed.size(), bonds.size());
    EXPECT_EQ(state.failed_in_order.size(), bonds.size());
    // Dissipated energy (THEORY §5): each bond's ½ W ᾱ c (s_crit |ξ|)² =
    // ½ k |ξ|⁴ s_crit²; the overshoot is what it held beyond that (> 0: every
    // selected bond is over s_crit), and the two add up to the energy held.
    double critical = 0.0, held = 0.0;
    for (const auto& b : bonds) {
      critical += 0.5 * b.k * std::pow(b.xi.squaredNorm(), 2) * failure.s_crit() * failure.s_crit();
      held += b.energy;
    }
    EXPECT_NEAR(state.energy.dissipated, critical, 1e-12 * critical);
    EXPECT_NEAR(state.energy.dissipated + state.energy.overshoot, held, 1e-12 * held);
    EXPECT_GT(state.energy.overshoot, 0.0);
    EXPECT_EQ(energy.dissipated, state.energy.dissipated);
    EXPECT_EQ(energy.overshoot, state.energy.overshoot);
    // Reference: reassembled without the failed bonds, then constrained.
    const system::ConstrainedSystem ref(model, system::assemble_stiffness(model, &state.failed).K,
                                        setup::build_dirichlet(model), no_force);
    const la::Matrix& A_ref = ref.A();
    const la::Vector& rhs_ref = ref.rhs_unit();
    const Eigen::MatrixXd Kd = K.to_dense(), Kr = ref.K().to_dense();
    const double scale = Kr.cwiseAbs().maxCoeff();
    const double dK = (Kd - Kr).cwiseAbs().maxCoeff() / scale;
    const double dA = (A.to_dense() - A_ref.to_dense()).cwiseAbs().maxCoeff() / scale;
    const auto r1 = rhs.to_std(), r2 = rhs_ref.to_std();
    double dr = 0.0, rmax = 0.0;
    for (std::size_t k = 0; k < r1.size(); ++k) {
      dr = std::max(dr, std::abs(r1[k] - r2[k]));
      rmax = std::max(rmax, std::abs(r2[k]));
    }
    std::printf("%dD: %zu bonds failed; downdate vs reassembly: K %.2e, A %.2e, rhs %.2e (relative)\n", dim,
                bonds.size(), dK, dA, dr / rmax);
    EXPECT_LT(dK, 1e-13);
    EXPECT_LT(dA, 1e-13);
    EXPECT_LT(dr, 1e-13 * rmax);
    if (at_edge) {
      const auto r0 = rhs_intact.to_std();
      double changed = 0.0;
      for (std::size_t k = 0; k < r0.size(); ++k) changed = std::max(changed, std::abs(r1[k] - r0[k]));
      EXPECT_GT(changed, 1e-6 * rmax) << "no failed bond reached a prescribed dof: the rhs check is vacuous";
    }
    EXPECT_GT((Kd - K_intact).cwiseAbs().maxCoeff(), 1e-6 * scale);  // the failures did change K
    // Failed bonds never come back: a larger displacement finds none of them.
    for (double& v : state.u) v *= 10.0;
    for (const auto& b : failure.select(state)) EXPECT_FALSE(state.failed.contains(b.id));
  }
}

TEST(Fracture, FailureStartsAtThePredictedLoad) {
  for (int dim : {1, 2, 3}) {
    SCOPED_TRACE(::testing::Message() << dim << "D");
    const double s_crit = 1e-3;
    const double per_load = max_stretch_per_load(pulled_case(dim, {1.0}, s_crit));
    const double lambda_crit = s_crit / per_load;
    std::printf("%dD: max stretch / applied strain %.6f, predicted failure load factor %.6f\n", dim,
                per_load / 1e-3, lambda_crit);
    // Bonds along x carry at least the applied strain; more where the strain
    // concentrates (the coupling's strain error, the soft free faces in 2D).
    EXPECT_GE(per_load / 1e-3, 1.0 - 1e-9);
    const auto c = pulled_case(
        dim, {0.5 * lambda_crit, 0.99 * lambda_crit, 1.01 * lambda_crit, 1.2 * lambda_crit}, s_crit);
    const auto model = setup::build_discretization(c);
    const auto run = run::run_static(model, {scratch_dir("predicted"), true});
    ASSERT_EQ(run.history.size(), 4u);
    for (const auto& r : run.history)
      std::printf("  load %.4f: %zu bonds failed (%d iterations), reaction %.4e, W %.6e, U %.6e, D %.6e\n",
                  r.load_factor, r.bonds_broken, r.break_iterations, r.reactions.back().x(), r.external_work,
                  r.strain_energy, r.dissipated);
    EXPECT_EQ(run.history[0].bonds_broken, 0u);
    EXPECT_EQ(run.history[1].bonds_broken, 0u);
    EXPECT_GT(run.history[2].bonds_broken, 0u);
    // Energy bookkeeping: W = U before any failure; after, W − U − D ≥ 0
    // (D at s_crit) and W − U − D − overshoot ≥ 0 (released_energy).
    for (int i = 0; i < 2; ++i) {
      const auto& r = run.history[static_cast<std::size_t>(i)];
      EXPECT_NEAR(r.external_work, r.strain_energy, 1e-9 * r.strain_energy);
      EXPECT_EQ(r.dissipated, 0.0);
    }
    for (std::size_t i = 2; i < run.history.size(); ++i) {
      const auto& r = run.history[i];
      EXPECT_GT(r.dissipated, 0.0);
      EXPECT_GE(r.overshoot, 0.0);
      EXPECT_GE(r.external_work - r.strain_energy - r.dissipated, -1e-9 * r.external_work)
          << "W - U - D at increment " << i + 1;
      EXPECT_GE(r.released, -1e-9 * r.external_work) << "W - U - D - overshoot at increment " << i + 1;
      EXPECT_NEAR(r.released, r.external_work - r.strain_energy - r.dissipated - r.overshoot,
                  1e-12 * r.external_work);
      EXPECT_GE(r.bonds_broken, run.history[i - 1].bonds_broken);  // never heal
    }
  }
}

TEST(Fracture, SameBondsFailWithOneAndTwoThreads) {
  const auto c = pulled_case(2, {0.8, 1.05, 1.2, 1.4}, 1e-3);
  const auto model = setup::build_discretization(c);
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const auto one = run::run_static(model, {scratch_dir("threads1"), true});
  omp_set_num_threads(2);
  const auto two = run::run_static(model, {scratch_dir("threads2"), true});
  omp_set_num_threads(saved);
  ASSERT_EQ(one.history.size(), two.history.size());
  bool any = false;
  for (std::size_t i = 0; i < one.history.size(); ++i) {
    EXPECT_EQ(one.history[i].bonds_broken, two.history[i].bonds_broken) << "increment " << i + 1;
    EXPECT_EQ(one.history[i].break_iterations, two.history[i].break_iterations);
    EXPECT_EQ(one.history[i].dissipated, two.history[i].dissipated);
    any = any || one.history[i].bonds_broken > 0;
  }
  EXPECT_TRUE(any) << "no bond failed: the test would be vacuous";
  EXPECT_EQ(one.displacement, two.displacement);
}

// The interfaces of each part's cells (a process's share of the crack area,
// issue 17), put together in cell order, are the whole list: the same pairs,
// bond counts and failed counts, some failed.
TEST(Fracture, InterfacesOfThePartsMakeTheWholeList) {
  const auto model = setup::build_discretization(pulled_case(2, {1.0}, 1e-3));
  bonds::BrokenBonds failed(model.mesh.num_cells(), model.nonlocal->points.per_cell);
  for (Index e = 0; e < model.mesh.num_cells(); e += 5)
    for (Index f : model.nonlocal->graph.row(e))
      if (f > e) failed.add({e, f, 0, 1});
  const auto space = model.nonlocal_space(&failed);
  const auto whole = assembly::interface_bonds(space);
  ASSERT_FALSE(whole.empty());
  EXPECT_TRUE(std::any_of(whole.begin(), whole.end(), [](const auto& i) { return i.failed > 0; }));
  for (int parts : {2, 3}) {
    std::vector<assembly::InterfaceBonds> joined;
    for (int q = 0; q < parts; ++q) {
      const auto mine = assembly::interface_bonds(space, partition::cells_of_part(model.mesh, parts, q));
      joined.insert(joined.end(), mine.begin(), mine.end());
    }
    std::stable_sort(joined.begin(), joined.end(), [](const auto& a, const auto& b) { return a.e < b.e; });
    ASSERT_EQ(joined.size(), whole.size()) << parts;
    for (std::size_t k = 0; k < whole.size(); ++k) {
      EXPECT_EQ(joined[k].e, whole[k].e);
      EXPECT_EQ(joined[k].f, whole[k].f);
      EXPECT_EQ(joined[k].axis, whole[k].axis);
      EXPECT_EQ(joined[k].total, whole[k].total);
      EXPECT_EQ(joined[k].failed, whole[k].failed);
    }
  }
}

// [fracture] no_fail: a bond with an end in a listed region is never
// selected; intra_cell_failure = false: no bond between two points of one
// cell is; the others are selected exactly as without the options.
TEST(Fracture, NoFailRegionsAndIntraCellRuleFilterTheSelection) {
  auto c = pulled_case(2, {1.0}, 1e-3);
  const ElasticState run = elastic_state(c);
  // A threshold that most of the non-local zone's x-bonds exceed.
  c.fracture.s_crit = 0.5 * run.max_stretch;
  casefile::RegionSpec left;
  left.name = "left_half";
  left.id = 1;
  left.lower = Vec3(-1.0, -1.0, 0.0);
  left.upper = Vec3(2.0, 3.0, 0.0);
  c.regions = {left};
  const auto free_model = setup::build_discretization(c);
  const auto expected = evolution::BondFailure(free_model).select(state_at(free_model, run.u));
  c.fracture.no_fail = {"left_half"};
  const auto kept_model = setup::build_discretization(c);
  const auto selected = evolution::BondFailure(kept_model).select(state_at(kept_model, run.u));
  const auto& in_left = kept_model.mesh.cell_sets.at("left_half");
  auto is_left = [&](Index cell) { return std::binary_search(in_left.begin(), in_left.end(), cell); };
  ASSERT_TRUE(std::is_sorted(in_left.begin(), in_left.end()));
  std::size_t outside = 0, touching = 0;
  for (const auto& b : expected) (is_left(b.id.e) || is_left(b.id.f) ? touching : outside) += 1;
  std::printf("bonds over 0.5 s_max: %zu, %zu of them touch the no-fail half\n", expected.size(), touching);
  ASSERT_GT(touching, 0u) << "the region holds no candidate bond: the test would be vacuous";
  ASSERT_GT(outside, 0u);
  ASSERT_EQ(selected.size(), outside);
  for (const auto& b : selected) {
    EXPECT_FALSE(is_left(b.id.e) || is_left(b.id.f));
  }
  // intra_cell_failure = false: the same selection less the bonds inside one cell.
  c.fracture.no_fail.clear();
  c.fracture.intra_cell_failure = false;
  const auto inter_model = setup::build_discretization(c);
  const auto inter = evolution::BondFailure(inter_model).select(state_at(inter_model, run.u));
  std::size_t intra = 0;
  for (const auto& b : expected) intra += b.id.e == b.id.f ? 1 : 0;
  ASSERT_GT(intra, 0u) << "no intra-cell bond over the threshold: the check would be vacuous";
  ASSERT_EQ(inter.size(), expected.size() - intra);
  for (const auto& b : inter) EXPECT_NE(b.id.e, b.id.f);
  c.fracture.intra_cell_failure = true;
  c.fracture.no_fail = {"left_half"};
  // Through the whole run: with the region covering the block nothing fails.
  left.upper = Vec3(5.0, 3.0, 0.0);
  c.regions = {left};
  c.loading.factors = {1.0};
  const auto none = run::run_static(setup::build_discretization(c), {scratch_dir("nofail_all"), true});
  EXPECT_EQ(none.history.back().bonds_broken, 0u);  // `expected` shows bonds over s_crit at this load
}

TEST(Fracture, IterationCapStopsWithAMessageAndKeepsResults) {
  // Only the most stretched bonds fail per iteration: the bar needs many.
  auto c = pulled_case(1, {0.5, 1.05}, 1e-3);
  c.fracture.rule = casefile::BreakRule::fraction;
  c.fracture.fraction = 0.9999;
  c.fracture.max_iterations = 2;
  const auto model = setup::build_discretization(c);
  const auto dir = scratch_dir("cap");
  try {
    (void)run::run_static(model, {dir, true});
    FAIL() << "expected the iteration cap to stop the run";
  } catch (const Error& e) {
    const std::string msg = e.what();
    std::printf("%s\n", msg.c_str());
    EXPECT_NE(msg.find("increment 2/2"), std::string::npos) << msg;
    EXPECT_NE(msg.find("max_iterations"), std::string::npos) << msg;
    // How many bonds were still failing, and the files that keep the state.
    EXPECT_NE(msg.find("more are over the criterion now"), std::string::npos) << msg;
    EXPECT_NE(
        msg.find("kept as increment 2: its row in " + (std::filesystem::path(dir) / "test.csv").string()),
        std::string::npos)
        << msg;
    EXPECT_NE(msg.find((std::filesystem::path(dir) / "test_failures.csv").string()), std::string::npos)
        << msg;
  }
  EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(dir) / "test.csv"));
  // The CSV has the stopped increment's row: its state after the last iteration.
  const auto rows = read_rows((std::filesystem::path(dir) / "test.csv").string());
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[1].at("increment"), 2.0);
  EXPECT_EQ(rows[1].at("break_iterations"), 2.0);
  EXPECT_GT(rows[1].at("bonds_broken_increment"), 0.0);
  EXPECT_GE(rows[1].at("external_work") - rows[1].at("strain_energy") - rows[1].at("dissipated_energy"),
            -1e-12);
}

// [output] failed_bonds: one row per failed bond, over s_crit, shorter than
// the horizon's reach; the rows add up to the run's failed-bond count and to
// its dissipated and overshoot energies (THEORY §5).
TEST(Fracture, FailedBondsFileAddsUpToTheEnergyColumns) {
  for (int dim : {2, 3}) {
    SCOPED_TRACE(::testing::Message() << dim << "D");
    auto c = pulled_case(dim, {0.8, 1.05, 1.2, 1.4}, 1e-3);
    c.output.failed_bonds = true;
    c.output.basename = "pulled";
    const auto model = setup::build_discretization(c);
    const std::string dir = scratch_dir("failed_bonds" + std::to_string(dim));
    const auto run = run::run_static(model, {dir, true});
    const auto& last = run.history.back();
    ASSERT_GT(last.bonds_broken, 0u) << "no bond failed: the test would be vacuous";
    const auto rows = read_rows((std::filesystem::path(dir) / "pulled_failed_bonds.csv").string());
    ASSERT_EQ(rows.size(), last.bonds_broken);
    double dissipated = 0.0, overshoot = 0.0;
    const double reach = model.nonlocal->points.bond_reach(model.nonlocal->kernel.horizon);
    for (const auto& r : rows) {
      EXPECT_GT(r.at("stretch"), 1e-3);
      const Vec3 xi(r.at("xh") - r.at("xg"), r.at("yh") - r.at("yg"), r.at("zh") - r.at("zg"));
      EXPECT_LT(xi.norm(), reach);
      // ½ k |ξ|⁴ s² scales with s²: the two energies are in the ratio s_crit² : s² − s_crit².
      const double s = r.at("stretch") / 1e-3;
      EXPECT_NEAR(r.at("overshoot_energy"), r.at("dissipated_energy") * (s * s - 1.0),
                  1e-9 * r.at("dissipated_energy") * s * s);
      dissipated += r.at("dissipated_energy");
      overshoot += r.at("overshoot_energy");
    }
    EXPECT_NEAR(dissipated, last.dissipated, 1e-12 * last.dissipated);
    EXPECT_NEAR(overshoot, last.overshoot, 1e-12 * last.dissipated);

    // BASENAME_failures.csv: one row per bond-breaking iteration, whose bonds
    // add up to the failed-bond file's, each with its re-solve and its time.
    const auto iterations = read_rows((std::filesystem::path(dir) / "pulled_failures.csv").string());
    ASSERT_FALSE(iterations.empty());
    double bonds = 0.0, seconds = 0.0;
    for (const auto& r : iterations) {
      bonds += r.at("bonds_failed");
      EXPECT_GE(r.at("solver_iterations"), 0.0);
      EXPECT_TRUE(r.at("preconditioner_rebuilt") == 0.0 || r.at("preconditioner_rebuilt") == 1.0);
      EXPECT_GE(r.at("wall_time"), 0.0);
      seconds += r.at("wall_time");
    }
    EXPECT_EQ(bonds, static_cast<double>(rows.size()));
    // Each row times its own iteration (not the time since the start): together
    // they fit in the run.
    EXPECT_LE(seconds, last.wall_time);
  }
}

}  // namespace
}  // namespace perimorph
