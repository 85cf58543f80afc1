// Benchmark of the local (FEM) elasticity path on a unit cube of N³ hex cells,
// through the library's own calls (as run/static_run.cpp does):
//   matrix_create/N   build_sparsity + la::Matrix (exact preallocation)
//   assemble/N        assemble_elasticity + finalize (Q1, 2×2×2 Gauss points)
//   solve_<solver>/N  LinearSolver construction, set_operator and solve: CG +
//                     GAMG with the rigid-body near-null space (the default,
//                     rtol 1e-8) or MUMPS Cholesky (-ksp_type preonly
//                     -pc_type cholesky -pc_factor_mat_solver_type mumps);
//                     the time includes the preconditioner setup
//                     (GAMG hierarchy, MUMPS analysis and factorization).
// Material: isotropic E = 1, ν = 0.25. Boundary: u = 0 on face set "zmin",
// u = (0, 0, 0.01) on "zmax" (every component on both).
//
// Times are wall-clock (real_time); cpu_time is the process's CPU time.
// Counters: cells, dofs, nnz (Matrix::nonzeros), ksp_iterations (the
// solver's; Google Benchmark's own "iterations" counts repetitions), rel_residual
// (true residual ||b − A u|| / ||b||), u_norm (to compare solvers), and
// peak_rss_mb: getrusage's ru_maxrss after the benchmark. Before each benchmark
// the process's peak is reset (malloc_trim, then "5" written to
// /proc/self/clear_refs), so the value is that benchmark's own peak, set-up
// included; rss_reset = 0 says the reset failed and the value is the
// process's peak so far.
//
// Run: bench/run_local_bench.sh (Release build, JSON in bench/results/,
// table in docs/benchmarks/local-elasticity.md). Arguments after the
// benchmark's own (--benchmark_filter=..., ...) go to PETSc.

#include "perimorph/assembly/local_assembly.hpp"
#include "perimorph/assembly/sparsity.hpp"
#include "perimorph/dofs/dof_map.hpp"
#include "perimorph/fem/constitutive_field.hpp"
#include "perimorph/fem/material.hpp"
#include "perimorph/fem/quadrature.hpp"
#include "perimorph/la/linear_solver.hpp"
#include "perimorph/la/matrix.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/la/vector.hpp"
#include "perimorph/mesh/box.hpp"
#include "perimorph/mesh/mesh.hpp"

#include <benchmark/benchmark.h>

#include <sys/resource.h>

#include <malloc.h>

#include <algorithm>
#include <exception>
#include <fstream>
#include <string>
#include <vector>

namespace {

using namespace perimorph;

constexpr int kDim = 3;
constexpr double kRtol = 1e-8;
constexpr int kMaxIterations = 10000;
constexpr double kTopDisplacement = 0.01;

/// Resets the process's peak resident set size to the current one. Returns
/// false where the kernel does not allow it.
bool reset_peak_rss() {
  malloc_trim(0);
  std::ofstream clear("/proc/self/clear_refs");
  if (!clear) return false;
  clear << "5";
  clear.flush();
  return static_cast<bool>(clear);
}

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

/// The unit cube with N³ cells, its dof map, quadrature rule and stiffness.
struct Problem {
  mesh::Mesh mesh;
  dofs::DofMap dofmap;
  std::vector<fem::QuadraturePoint> rule;
  fem::ConstitutiveField stiffness;

  explicit Problem(Index n)
      : mesh(mesh::make_box({kDim, Vec3::Zero(), Vec3::Ones(), {n, n, n}})),
        dofmap(mesh, kDim),
        rule(fem::gauss_legendre(kDim, 2)),
        stiffness(kDim, mesh.num_cells(), static_cast<int>(rule.size())) {
    const Voigt6 C = fem::stiffness_voigt(fem::IsotropicElasticity{1.0, 0.25});
    const int id = stiffness.add_tensor(fem::reduce_stiffness(C, kDim, fem::PlaneMode::strain));
    for (Index c = 0; c < mesh.num_cells(); ++c) stiffness.set_cell(c, id);
  }

  assembly::LocalSpace space() const { return {mesh, dofmap, rule, 1.0}; }
};

/// Sorted constrained dofs and the full-length vector of prescribed values.
struct Dirichlet {
  std::vector<Index> dofs;
  std::vector<double> values;
};

Dirichlet dirichlet(const Problem& p) {
  Dirichlet bc;
  bc.values.assign(static_cast<std::size_t>(p.dofmap.num_dofs()), 0.0);
  const auto prescribe = [&](const std::string& set, const Vec3& u) {
    for (Index node : p.dofmap.dof_nodes_of_mesh_nodes(p.mesh.nodes_of_set(set)))
      for (int d = 0; d < kDim; ++d) {
        bc.dofs.push_back(node * kDim + d);
        bc.values[static_cast<std::size_t>(node * kDim + d)] = u[d];
      }
  };
  prescribe("zmin", Vec3::Zero());
  prescribe("zmax", Vec3(0.0, 0.0, kTopDisplacement));
  std::sort(bc.dofs.begin(), bc.dofs.end());
  bc.dofs.erase(std::unique(bc.dofs.begin(), bc.dofs.end()), bc.dofs.end());
  return bc;
}

void set_size_counters(benchmark::State& state, const Problem& p, double nnz) {
  state.counters["cells"] = static_cast<double>(p.mesh.num_cells());
  state.counters["dofs"] = static_cast<double>(p.dofmap.num_dofs());
  state.counters["nnz"] = nnz;
}

void set_rss_counters(benchmark::State& state, bool reset) {
  state.counters["peak_rss_mb"] = peak_rss_mb();
  state.counters["rss_reset"] = reset ? 1.0 : 0.0;
}

// (a) sparsity pattern and PETSc matrix with exact preallocation.
void matrix_create(benchmark::State& state) {
  const bool reset = reset_peak_rss();
  const Problem p(static_cast<Index>(state.range(0)));
  double nnz = 0.0;
  for (auto _ : state) {
    la::Matrix K(assembly::build_sparsity(p.dofmap));
    nnz = K.nonzeros();
    benchmark::DoNotOptimize(nnz);
  }
  set_size_counters(state, p, nnz);
  set_rss_counters(state, reset);
}

// (b) stiffness assembly into a created matrix, then finalize.
void assemble(benchmark::State& state) {
  const bool reset = reset_peak_rss();
  const Problem p(static_cast<Index>(state.range(0)));
  la::Matrix K(assembly::build_sparsity(p.dofmap));
  for (auto _ : state) {
    state.PauseTiming();
    K.zero_entries();
    state.ResumeTiming();
    assembly::assemble_elasticity(p.space(), p.stiffness, K);
    K.finalize();
  }
  set_size_counters(state, p, K.nonzeros());
  set_rss_counters(state, reset);
}

enum class Solver { cg_gamg, mumps_cholesky };

void select_solver(Solver s) {
  // Clear first so that nothing from a previous benchmark leaks into this one.
  for (const char* name : {"-ksp_type", "-pc_type", "-pc_factor_mat_solver_type"}) la::clear_option(name);
  if (s == Solver::mumps_cholesky) {
    la::set_option("-ksp_type", "preonly");
    la::set_option("-pc_type", "cholesky");
    la::set_option("-pc_factor_mat_solver_type", "mumps");
  }
}

// (c), (d) solve of the constrained system, preconditioner set-up included.
void solve(benchmark::State& state, Solver s) {
  const bool reset = reset_peak_rss();
  select_solver(s);
  const Problem p(static_cast<Index>(state.range(0)));
  const Index n = p.dofmap.num_dofs();
  la::Matrix A(assembly::build_sparsity(p.dofmap));
  assembly::assemble_elasticity(p.space(), p.stiffness, A);
  A.finalize();
  const Dirichlet bc = dirichlet(p);
  la::Vector g(n, kDim), rhs(n, kDim), u(n, kDim);
  g.assign(bc.values);
  rhs.set_all(0.0);
  A.eliminate_dirichlet(bc.dofs, g, rhs);
  A.set_spd();

  la::SolveReport report;
  for (auto _ : state) {
    state.PauseTiming();
    u.set_all(0.0);  // every repetition starts from the same guess
    state.ResumeTiming();
    try {
      la::LinearSolver solver(kRtol, kMaxIterations);
      solver.set_operator(A, p.dofmap.node_coordinate_on(p.mesh), kDim);
      report = solver.solve(rhs, u);
    } catch (const std::exception& e) {
      state.SkipWithError(e.what());
      break;
    }
  }
  set_size_counters(state, p, A.nonzeros());
  state.counters["ksp_iterations"] = static_cast<double>(report.iterations);
  state.counters["rel_residual"] = report.relative_residual;
  state.counters["u_norm"] = u.norm2();
  state.SetLabel(report.ksp_type + "+" + report.pc_type);
  set_rss_counters(state, reset);
}

/// Few repetitions for the small cases, one for the large ones.
int repetitions(int n) {
  return n <= 20 ? 5 : n <= 40 ? 2 : 1;
}

void register_all() {
  const std::vector<int> sizes{20, 40, 60};
  for (int n : sizes)
    benchmark::RegisterBenchmark("matrix_create", matrix_create)
        ->Arg(n)
        ->Unit(benchmark::kMillisecond)
        ->MeasureProcessCPUTime()
        ->Iterations(repetitions(n));
  for (int n : sizes)
    benchmark::RegisterBenchmark("assemble", assemble)
        ->Arg(n)
        ->Unit(benchmark::kMillisecond)
        ->MeasureProcessCPUTime()
        ->Iterations(repetitions(n));
  for (int n : sizes)
    benchmark::RegisterBenchmark("solve_cg_gamg", solve, Solver::cg_gamg)
        ->Arg(n)
        ->Unit(benchmark::kMillisecond)
        ->MeasureProcessCPUTime()
        ->Iterations(n <= 20 ? 3 : 1);
  for (int n : sizes)
    benchmark::RegisterBenchmark("solve_mumps_cholesky", solve, Solver::mumps_cholesky)
        ->Arg(n)
        ->Unit(benchmark::kMillisecond)
        ->MeasureProcessCPUTime()
        ->Iterations(n <= 20 ? 3 : 1);
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);  // removes the --benchmark_* arguments
  la::PetscSession petsc(argc, argv);  // the rest are PETSc options
  register_all();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
