#pragma once
// The benchmarks run under mpirun -n P (issue 17): every process runs every
// benchmark in step, each iteration timed from a barrier, and process 0 alone
// reports.

#include "perimorph/la/petsc_session.hpp"

#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdio>

namespace perimorph::bench {

/// Times `work` once an iteration, each started at a barrier (manual time).
template <class Work>
void time_collectively(benchmark::State& state, Work&& work) {
  for (auto _ : state) {
    la::barrier();
    const auto t0 = std::chrono::steady_clock::now();
    work();
    state.SetIterationTime(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
}

/// Runs the registered benchmarks, process 0 reporting; returns main's code.
inline int run_reported_by_process_zero() {
  if (la::world_rank() != 0) std::freopen("/dev/null", "w", stdout);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

}  // namespace perimorph::bench
