// Cost of one bond-breaking iteration (issue 5, THEORY §5;
// docs/benchmarks/fracture-update.md): the incremental update of K, A and the
// right-hand side (evolution::BondFailure::apply) against a full reassembly, on
// the B6 geometry (BENCHMARKS.md): block 12δ × 8δ × 2δ, δ = 1, gaussian
// kernel l = δ/3, E = 300 GPa, ν = 1/4, pre-crack cut in the plane y = 4 for
// x < 4, α = 1 in the box x ≥ 3, 3 ≤ y ≤ 5 (all z) with a cubic transition
// 1.5 wide, DG where purely non-local, 2×2×2 non-local points per cell;
// h = δ, δ/2, 0.4δ (nx = 12, 24, 30 cells along x). The crack is opened by
// u = (0, ±u_d, 0) on the top and bottom faces for x ≤ 2 (all components
// prescribed there), u_d = 0.01.
//
// Per mesh, once, not timed: build_discretization, assemble_stiffness, A = K with the
// constraints eliminated, the elastic solution u at load factor 1 (CG + GAMG,
// the default solver) and the stretches of every bond in tension at u; the
// 1000 most stretched bonds are the ones broken below (in select's order).
//
//   FullReassembly/nx     what a reassembling code does per iteration, with
//                         the 100 most stretched bonds failed:
//                         assemble_stiffness(model, &broken) (pattern and
//                         matrix creation, local and non-local assembly), then
//                         A = K.duplicate(), eliminate_dirichlet, set_spd
//   Select/nx/k           BondFailure::select(u) with s_crit between the k-th
//                         and (k+1)-th largest stretch: a pass over every bond
//   Apply/nx/k            BondFailure::apply of the k most stretched bonds to
//                         fresh copies of K, A and the right-hand side, then
//                         PartSupport's inspect and apply (detached dofs,
//                         parts cut free), as one pass of the run's
//                         components (copies made outside the timed region)
//   Solve/nx              after applying the 100 most stretched bonds:
//                         set_operator(A) and one solve warm-started from u,
//                         as the run does (run/quasi_static_run.cpp) (includes the GAMG
//                         set-up); then the same solve again without
//                         set_operator (preconditioner reused), counter
//                         solve_only_s
//   Fields/nx, CrackArea/nx   BondFailure::fields() (damage and dissipation
//                         per cell, for the VTU) and crack_area() (CSV), after
//                         the 100 most stretched bonds failed
//   FloatingParts/nx       evolution::find_floating_parts (the connected parts of
//                         the stiffness graph and their free rigid-body
//                         modes), which PartSupport runs when a cell pair has lost
//                         its last intact bond; same state
//
// Times: manual (steady_clock around the timed call), in ms. Each benchmark
// runs one iteration per repetition, 15 repetitions for Select and Apply, 5
// for Fields and CrackArea, 3 for FullReassembly and Solve; Google Benchmark
// adds their mean, median, standard deviation and cv (the report uses the
// median: the machine is shared). Counters: nx, cells, dofs, bonds (intact
// bonds of the model, NonlocalStats::bonds), tension_bonds (s > 0 at u), nnz
// (of K), threads; Select: k, s_crit, selected (bonds select returned),
// ns_per_bond (time / bonds); Apply: k, broken, energy (the energy the bonds
// held), us_per_bond (time / k); FullReassembly: assemble_s, create_s,
// local_s, nonlocal_s (assemble_stiffness's parts), constrain_s, bonds_after;
// Solve: ksp_iterations, rel_residual, solve_only_s, ksp_iterations_again,
// elastic_iterations; Fields: max_damage.
// Apply reports free dofs left without any bond (detached) on stderr; none
// are expected here. Arguments after the benchmark's own go to PETSc.
//
// Run: bench/run_fracture_bench.sh.

#include "b6_case.hpp"
#include "perimorph/assembly/bond_stretch.hpp"
#include "perimorph/evolution/bond_failure.hpp"
#include "perimorph/evolution/floating_parts.hpp"
#include "perimorph/evolution/part_support.hpp"
#include "perimorph/la/linear_solver.hpp"
#include "perimorph/la/matrix.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/la/vector.hpp"
#include "perimorph/setup/boundary_conditions.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/system/stiffness.hpp"

#include <benchmark/benchmark.h>
#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <limits>
#include <memory>
#include <numeric>
#include <string>
#include <tuple>
#include <vector>

namespace {

using namespace perimorph;
using Clock = std::chrono::steady_clock;

constexpr int kDim = 3;
constexpr std::size_t kMaxK = 1000;   // most bonds broken in one update
constexpr std::size_t kStateK = 100;  // failed bonds for FullReassembly, Solve, Fields
constexpr int kSizes[] = {12, 24, 30};
constexpr int kCounts[] = {1, 10, 100, 1000};

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// One mesh: the model, the intact matrices, the elastic solution and the
/// most stretched bonds. Built once per nx, not timed.
struct Setup {
  int nx;
  setup::Discretization model;
  setup::DirichletData bc;
  system::AssembledStiffness intact;
  la::Matrix A;
  la::Vector g, rhs_unit;
  std::vector<double> u;
  std::size_t tension = 0;                   ///< bonds with s > 0 at u
  std::vector<double> stretch;               ///< the kMaxK + 1 largest stretches, descending
  std::vector<assembly::StretchedBond> top;  ///< the kMaxK most stretched, descending
  la::SolveReport elastic;

  explicit Setup(int n)
      : nx(n),
        model(setup::build_discretization(bench::b6_case(n))),
        bc(setup::build_dirichlet(model)),
        intact(system::assemble_stiffness(model)),
        A(intact.K.duplicate()),
        g(dofs(), kDim),
        rhs_unit(dofs(), kDim) {
    std::vector<double> gv(static_cast<std::size_t>(dofs()), 0.0);
    for (std::size_t k = 0; k < bc.dofs.size(); ++k) gv[static_cast<std::size_t>(bc.dofs[k])] = bc.values[k];
    g.assign(gv);
    rhs_unit.set_all(0.0);
    A.eliminate_dirichlet(bc.dofs, g, rhs_unit);
    A.set_spd();
    la::LinearSolver solver(model.config.solver.rtol, model.config.solver.max_iterations);
    solver.set_operator(A, model.dofmap.node_coordinate_on(model.mesh), kDim);
    la::Vector x(dofs(), kDim);
    x.set_all(0.0);
    elastic = solver.solve(rhs_unit, x);
    u = x.to_std();

    const evolution::BondFailure failure(model);
    const evolution::RunState intact_state(model);
    auto all = assembly::bonds_over(failure.space(intact_state), u, 0.0);
    tension = all.size();
    std::vector<std::size_t> order(all.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    const std::size_t keep = std::min(kMaxK + 1, all.size());
    std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(keep), order.end(),
                      [&](std::size_t a, std::size_t b) { return all[a].stretch > all[b].stretch; });
    order.resize(keep);
    for (std::size_t i : order) stretch.push_back(all[i].stretch);
    order.resize(std::min(kMaxK, keep));
    for (std::size_t i : order) top.push_back(all[i]);
  }

  Index dofs() const { return model.dofmap.num_dofs(); }

  /// The k most stretched bonds, in select's order (e, f, g, h).
  std::vector<assembly::StretchedBond> most_stretched(std::size_t k) const {
    std::vector<assembly::StretchedBond> out(top.begin(), top.begin() + static_cast<std::ptrdiff_t>(k));
    std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
      return std::tie(a.id.e, a.id.f, a.id.g, a.id.h) < std::tie(b.id.e, b.id.f, b.id.g, b.id.h);
    });
    return out;
  }

  /// s_crit between the k-th and (k+1)-th largest stretch.
  double threshold(std::size_t k) const { return 0.5 * (stretch[k - 1] + stretch[k]); }
};

std::unique_ptr<Setup> g_setup;

Setup& setup_for(int nx) {
  if (!g_setup || g_setup->nx != nx) {
    g_setup.reset();
    const auto t0 = Clock::now();
    g_setup = std::make_unique<Setup>(nx);
    const Setup& s = *g_setup;
    std::fprintf(stderr,
                 "nx=%d: %lld cells, %lld dofs, %zu bonds (%zu in tension at u), nnz(K) %.0f; set-up %.1f s "
                 "(assembly %.2f s, elastic solve %d its); largest stretch %.4e, 1000th %.4e\n",
                 nx, static_cast<long long>(s.model.mesh.num_cells()), static_cast<long long>(s.dofs()),
                 s.intact.nonlocal.bonds, s.tension, s.intact.K.nonzeros(), seconds_since(t0),
                 s.intact.local_seconds + s.intact.nonlocal_seconds + s.intact.setup_seconds,
                 s.elastic.iterations, s.stretch.front(), s.stretch.back());
  }
  return *g_setup;
}

/// A fresh constrained system (K, A and the right-hand side of the intact
/// model, as the run builds them), a run state with nothing failed, and the
/// run's two fracture components.
struct Copies {
  system::ConstrainedSystem sys;
  evolution::RunState state;
  evolution::BondFailure failure;
  evolution::PartSupport support;

  explicit Copies(Setup& s)
      : sys(s.model, s.intact.K.duplicate(), s.bc,
            std::vector<double>(static_cast<std::size_t>(s.dofs()), 0.0)),
        state(s.model),
        failure(s.model),
        support(s.model) {}

  /// What the run does with bonds over the criterion: bond failure's apply
  /// (downdates), then the support's inspect and apply (detached dofs, parts
  /// cut free).
  evolution::FailureEnergy apply(const std::vector<assembly::StretchedBond>& bonds) {
    const auto e = failure.apply(bonds, state, sys);
    if (!support.inspect(state, sys).quiet()) support.apply(state, sys);
    return e;
  }
};

void common_counters(benchmark::State& state, const Setup& s) {
  state.counters["nx"] = s.nx;
  state.counters["cells"] = static_cast<double>(s.model.mesh.num_cells());
  state.counters["dofs"] = static_cast<double>(s.dofs());
  state.counters["bonds"] = static_cast<double>(s.intact.nonlocal.bonds);
  state.counters["tension_bonds"] = static_cast<double>(s.tension);
  state.counters["nnz"] = s.intact.K.nonzeros();
  state.counters["threads"] = omp_get_max_threads();
}

benchmark::Counter mean(double sum) {
  return benchmark::Counter(sum, benchmark::Counter::kAvgIterations);
}

void BM_FullReassembly(benchmark::State& state) {
  Setup& s = setup_for(static_cast<int>(state.range(0)));
  bonds::BrokenBonds broken(s.model.mesh.num_cells(), s.model.nonlocal->points.per_cell);
  for (const auto& b : s.most_stretched(kStateK)) broken.add(b.id);
  double assemble = 0, create = 0, local = 0, nonlocal = 0, constrain = 0, bonds = 0;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    auto assembled = system::assemble_stiffness(s.model, &broken);
    const double t_assemble = seconds_since(t0);
    const auto t1 = Clock::now();
    la::Matrix A = assembled.K.duplicate();
    la::Vector rhs(s.dofs(), kDim);
    rhs.set_all(0.0);
    A.eliminate_dirichlet(s.bc.dofs, s.g, rhs);
    A.set_spd();
    const double t_constrain = seconds_since(t1);
    state.SetIterationTime(t_assemble + t_constrain);
    assemble += t_assemble;
    constrain += t_constrain;
    create += assembled.setup_seconds;
    local += assembled.local_seconds;
    nonlocal += assembled.nonlocal_seconds;
    bonds += static_cast<double>(assembled.nonlocal.bonds);
  }
  common_counters(state, s);
  state.counters["assemble_s"] = mean(assemble);
  state.counters["create_s"] = mean(create);
  state.counters["local_s"] = mean(local);
  state.counters["nonlocal_s"] = mean(nonlocal);
  state.counters["constrain_s"] = mean(constrain);
  state.counters["bonds_after"] = mean(bonds);
}

void BM_Select(benchmark::State& state) {
  Setup& s = setup_for(static_cast<int>(state.range(0)));
  const auto k = static_cast<std::size_t>(state.range(1));
  s.model.config.fracture.s_crit = s.threshold(k);
  const evolution::BondFailure failure(s.model);
  evolution::RunState at_u(s.model);
  at_u.u = s.u;
  double selected = 0, total = 0;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    const auto bonds = failure.select(at_u);
    const double t = seconds_since(t0);
    state.SetIterationTime(t);
    total += t;
    selected += static_cast<double>(bonds.size());
  }
  common_counters(state, s);
  state.counters["k"] = static_cast<double>(k);
  state.counters["s_crit"] = s.threshold(k);
  state.counters["selected"] = mean(selected);
  state.counters["ns_per_bond"] = mean(total * 1e9 / static_cast<double>(s.intact.nonlocal.bonds));
}

void BM_Apply(benchmark::State& state) {
  Setup& s = setup_for(static_cast<int>(state.range(0)));
  const auto k = static_cast<std::size_t>(state.range(1));
  const auto bonds = s.most_stretched(k);
  double total = 0, broken = 0, energy = 0;
  for (auto _ : state) {
    Copies c(s);
    const auto t0 = Clock::now();
    const auto e = c.apply(bonds);
    energy += e.dissipated + e.overshoot;
    const double t = seconds_since(t0);
    state.SetIterationTime(t);
    total += t;
    broken += static_cast<double>(c.state.failed.size());
    if (c.state.detached_dofs > 0)  // not a counter: always 0 here, its cv would be NaN in the JSON
      std::fprintf(stderr, "Apply nx=%d k=%zu: %zu detached dofs\n", s.nx, k, c.state.detached_dofs);
  }
  common_counters(state, s);
  state.counters["k"] = static_cast<double>(k);
  state.counters["broken"] = mean(broken);
  state.counters["energy"] = mean(energy);
  state.counters["us_per_bond"] = mean(total * 1e6 / static_cast<double>(k));
}

void BM_Solve(benchmark::State& state) {
  Setup& s = setup_for(static_cast<int>(state.range(0)));
  const auto bonds = s.most_stretched(kStateK);
  double its = 0, again = 0, its_again = 0, residual = 0;
  for (auto _ : state) {
    Copies c(s);
    c.apply(bonds);
    la::LinearSolver solver(s.model.config.solver.rtol, s.model.config.solver.max_iterations);
    la::Vector x(s.dofs(), kDim);
    x.assign(s.u);
    const auto t0 = Clock::now();
    solver.set_operator(c.sys.A(), s.model.dofmap.node_coordinate_on(s.model.mesh), kDim);
    const auto report = solver.solve(c.sys.rhs_unit(), x);
    state.SetIterationTime(seconds_since(t0));
    its += report.iterations;
    residual += report.relative_residual;
    x.assign(s.u);
    const auto t1 = Clock::now();
    const auto second = solver.solve(c.sys.rhs_unit(), x);
    again += seconds_since(t1);
    its_again += second.iterations;
  }
  common_counters(state, s);
  state.counters["ksp_iterations"] = mean(its);
  state.counters["rel_residual"] = mean(residual);
  state.counters["solve_only_s"] = mean(again);
  state.counters["ksp_iterations_again"] = mean(its_again);
  state.counters["elastic_iterations"] = s.elastic.iterations;
}

enum class Pass { fields, crack_area, floating_parts };

template <Pass kPass>
void BM_Output(benchmark::State& state) {
  Setup& s = setup_for(static_cast<int>(state.range(0)));
  Copies c(s);
  c.apply(s.most_stretched(kStateK));
  double check = 0;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    if constexpr (kPass == Pass::fields) {
      const auto f = c.failure.fields(c.state);
      benchmark::DoNotOptimize(f.damage.data());
      check += *std::max_element(f.damage.begin(), f.damage.end());
    } else if constexpr (kPass == Pass::crack_area) {
      const auto area = c.failure.crack_area(c.state);
      benchmark::DoNotOptimize(area);
    } else {
      const auto parts = evolution::find_floating_parts(
          s.model, evolution::stiffness_links(s.model, c.failure.space(c.state)), s.bc.dofs, {});
      benchmark::DoNotOptimize(parts.pins.data());
      check += parts.parts;
    }
    state.SetIterationTime(seconds_since(t0));
  }
  common_counters(state, s);
  // No crack_area counter: no face is fully broken by 100 bonds, and a
  // constant 0 has a NaN cv in the JSON.
  if constexpr (kPass == Pass::fields) state.counters["max_damage"] = mean(check);
}

void register_all() {
  // One iteration per repetition, many repetitions: the median is robust to
  // the other jobs on the shared machine.
  auto add = [](const char* name, auto fn, std::vector<int64_t> args, int repetitions) {
    std::vector<std::string> names{"nx", "k"};
    names.resize(args.size());
    benchmark::RegisterBenchmark(name, fn)
        ->ArgNames(names)
        ->Args(args)
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1)
        ->Repetitions(repetitions);
  };
  for (int nx : kSizes) {
    add("FullReassembly", BM_FullReassembly, {nx}, 3);
    for (int k : kCounts) add("Select", BM_Select, {nx, k}, 15);
    for (int k : kCounts) add("Apply", BM_Apply, {nx, k}, 15);
    add("Solve", BM_Solve, {nx}, 3);
    add("Fields", BM_Output<Pass::fields>, {nx}, 5);
    add("CrackArea", BM_Output<Pass::crack_area>, {nx}, 5);
    add("FloatingParts", BM_Output<Pass::floating_parts>, {nx}, 5);
  }
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  la::PetscSession petsc(argc, argv);
  benchmark::AddCustomContext("omp_threads", std::to_string(omp_get_max_threads()));
  benchmark::AddCustomContext("opening_u_d", fmt::format("{}", bench::kOpening));
  register_all();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  g_setup.reset();  // PETSc objects before PetscFinalize
  return 0;
}
