// Cost of growing α during a run (issue 14, THEORY §5; docs/benchmarks/remodel.md):
// the model rebuilt for the grown α (setup::rebuild_for_alpha) and the
// constrained system remodelled in the changed cells only (system::remodel),
// against assembling and constraining the system of the grown model from
// scratch, on the B6 geometry (bench/b6_case.hpp) at h = δ/2 and 0.4δ
// (nx = 24, 30). α grows by k balls of the thesis' rule (α = 1 to h + δ, 0 at
// h + 2δ) centred on the cells just ahead of the pre-crack front (x from 4,
// y = 4 ± h/2, z mid), k = 1, 4, 16: one cell, a short crack step, a long one.
//
//   Rebuild/nx/k     rebuild_for_alpha: non-local points, cell graph, morphed
//                    C, CG/DG flags and dof map for the grown α
//   Remodel/nx/k     system::remodel of a system assembled for the seed α (copy
//                    made outside the timed region); counters subtract_s,
//                    copy_s, add_s, constrain_s, changed_cells, dofs_before, dofs
//   Assemble/nx/k    assemble_stiffness of the grown model and its
//                    ConstrainedSystem (Dirichlet elimination): what a code
//                    without the partial update does after α grew
//
// Times: manual, ms; 3 repetitions each (the report uses the median).
// Run: BUILD_DIR=... then bench/remodel_bench --benchmark_repetitions=3.

#include "b6_case.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/setup/boundary_conditions.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/system/remodel.hpp"
#include "perimorph/system/stiffness.hpp"

#include <benchmark/benchmark.h>

#include <chrono>
#include <map>
#include <memory>
#include <utility>

namespace {

using namespace perimorph;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

struct Setup {
  setup::Discretization before, after;
  explicit Setup(int nx, int k) : before(setup::build_discretization(bench::b6_case(nx))), after(before) {
    const double h = 12.0 / nx;
    std::vector<alpha::Region> balls;
    for (int i = 0; i < k; ++i)
      for (double dy : {-0.5 * h, 0.5 * h})
        balls.push_back(
            {alpha::Ball{Vec3(4.0 + (i + 0.5) * h, 4.0 + dy, 1.0), h + 1.0}, 1.0, alpha::Profile::cubic});
    after = setup::rebuild_for_alpha(before, before.nonlocal->alpha.grown(std::move(balls), 3));
  }
};

Setup& setup_for(int nx, int k) {
  static std::map<std::pair<int, int>, std::unique_ptr<Setup>> cache;
  auto& s = cache[{nx, k}];
  if (!s) s = std::make_unique<Setup>(nx, k);
  return *s;
}

system::ConstrainedSystem constrained(const setup::Discretization& d) {
  return system::ConstrainedSystem(d, system::assemble_stiffness(d).K, setup::build_dirichlet(d),
                                   setup::build_external_force(d));
}

void Rebuild(benchmark::State& state) {
  const int nx = static_cast<int>(state.range(0)), k = static_cast<int>(state.range(1));
  Setup& s = setup_for(nx, k);
  for (auto _ : state) {
    const auto t0 = Clock::now();
    auto d = setup::rebuild_for_alpha(s.before, s.after.nonlocal->alpha);
    state.SetIterationTime(seconds_since(t0));
    benchmark::DoNotOptimize(d);
  }
}

void Remodel(benchmark::State& state) {
  const int nx = static_cast<int>(state.range(0)), k = static_cast<int>(state.range(1));
  Setup& s = setup_for(nx, k);
  system::Remodelled r;
  for (auto _ : state) {
    auto sys = constrained(s.before);
    const auto t0 = Clock::now();
    r = system::remodel(sys, s.before, s.after, nullptr, setup::build_dirichlet(s.after),
                        setup::build_external_force(s.after));
    state.SetIterationTime(seconds_since(t0));
  }
  state.counters["subtract_s"] = r.times.subtract;
  state.counters["copy_s"] = r.times.copy;
  state.counters["add_s"] = r.times.add;
  state.counters["constrain_s"] = r.times.constrain;
  state.counters["changed_cells"] = static_cast<double>(r.cells.size());
  state.counters["cells"] = static_cast<double>(s.before.mesh.num_cells());
  state.counters["dofs_before"] = static_cast<double>(s.before.dofmap.num_dofs());
  state.counters["dofs"] = static_cast<double>(s.after.dofmap.num_dofs());
}

void Assemble(benchmark::State& state) {
  const int nx = static_cast<int>(state.range(0)), k = static_cast<int>(state.range(1));
  Setup& s = setup_for(nx, k);
  for (auto _ : state) {
    const auto t0 = Clock::now();
    auto sys = constrained(s.after);
    state.SetIterationTime(seconds_since(t0));
    benchmark::DoNotOptimize(sys);
  }
}

void args(benchmark::internal::Benchmark* b) {
  for (int nx : {24, 30})
    for (int k : {1, 4, 16}) b->Args({nx, k});
  b->ArgNames({"nx", "k"})->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(1);
}

BENCHMARK(Rebuild)->Apply(args);
BENCHMARK(Remodel)->Apply(args);
BENCHMARK(Assemble)->Apply(args);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  la::PetscSession petsc(argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
