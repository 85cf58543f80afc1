// A process's piece of a model (issue 17, item 1; docs/benchmarks/
// distributed-runs.md, "The model cut to a piece"): what each process holds
// of a case's model today (its part: build_discretization with a ModelPart,
// mesh, dof map and per-cell arrays whole) against its piece
// (setup::cut_to_piece: the cells it reads, numbered locally), and what the
// cut and the assembly on each cost. Run under mpirun -n P (the assembly and
// the piece's numbering are collective):
//
//   mpirun -n 2 build/bench/piece_model_bench --case=bench/cases/b6_04_first12.toml
//
//   Cut        setup::cut_to_piece and system::piece_distribution
//   Assemble/0 K on the part, numbered by the whole model's dof numbering
//              (system::distribution_over_processes: what a run does today)
//   Assemble/1 K on the piece, numbered from the piece
//   Assemble/2 K on the part by the serial path (no distribution: what a run
//              on one process does; compare on one process only)
//
// Counters (the largest over the processes): cells (the part's: every cell;
// the piece's), model_MB (diagnostics::model_memory, plus on the piece its
// maps to global numbers and dof keys), and for the assembly its dof nodes
// (numbered: the whole model's, or the piece's). Times: manual (each
// iteration starts at a barrier), ms.

#include "perimorph/casefile/parse_case.hpp"
#include "perimorph/diagnostics/model_memory.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/partition/dof_layout.hpp"
#include "perimorph/partition/partition.hpp"
#include "perimorph/run/static_run.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/setup/piece_model.hpp"
#include "perimorph/system/piece_distribution.hpp"
#include "perimorph/system/stiffness.hpp"

#include "support/collective.hpp"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

namespace {

using namespace perimorph;

std::string case_path;

struct Model {
  setup::Discretization part;
  partition::Partition partition;
};

Model& model() {
  static std::unique_ptr<Model> m;
  if (m) return *m;
  const auto config = casefile::parse_case_file(case_path);
  auto part = run::process_part(config);
  auto p = partition::coordinate_bisection(part.mesh, la::world_size());
  m = std::make_unique<Model>(Model{std::move(part), std::move(p)});
  return *m;
}

double largest(double v) {
  return -static_cast<double>(la::min_over_processes({-static_cast<long long>(v)}).front());
}

double megabytes(const diagnostics::ModelMemory& m) {
  return static_cast<double>(m.whole() + m.points + m.graph + m.stiffness + m.piece_maps) / 1e6;
}

void cut(benchmark::State& state) {
  const Model& m = model();
  double cells = 0, mb = 0;
  bench::time_collectively(state, [&] {
    const auto piece =
        setup::cut_to_piece(m.part, m.partition.owner, la::world_rank(), la::any_over_processes);
    const auto d = system::piece_distribution(piece.piece->dofs);
    benchmark::DoNotOptimize(d->to_distributed.data());
    cells = static_cast<double>(piece.piece->global_cell.size());
    mb = megabytes(diagnostics::model_memory(piece));
  });
  state.counters["cells"] = largest(cells);
  state.counters["model_MB"] = largest(mb * 1e3) / 1e3;
  state.counters["part_cells"] = static_cast<double>(m.part.mesh.num_cells());
  state.counters["part_model_MB"] = largest(megabytes(diagnostics::model_memory(m.part)) * 1e3) / 1e3;
}

void assemble(benchmark::State& state) {
  const Model& m = model();
  const bool on_piece = state.range(0) == 1;
  const auto piece = setup::cut_to_piece(m.part, m.partition.owner, la::world_rank(), la::any_over_processes);
  const auto distribution =
      on_piece ? system::piece_distribution(piece.piece->dofs)
      : la::world_size() > 1
          ? system::distribution_over_processes(m.part)
          : system::distribution_of(partition::dof_numbering(m.part.dofmap, m.partition), 0);
  bench::time_collectively(state, [&] {
    if (state.range(0) == 2) {
      const auto K = system::assemble_stiffness(m.part);
      benchmark::DoNotOptimize(&K);
      return;
    }
    const auto K = system::assemble_stiffness(on_piece ? piece : m.part, distribution);
    benchmark::DoNotOptimize(&K);
  });
  state.counters["dof_nodes"] = largest(static_cast<double>(distribution->to_distributed.size()));
}

}  // namespace

int main(int argc, char** argv) {
  // --case=FILE is ours; the rest is Google Benchmark's.
  int kept = 1;
  for (int i = 1; i < argc; ++i)
    if (std::strncmp(argv[i], "--case=", 7) == 0)
      case_path = argv[i] + 7;
    else
      argv[kept++] = argv[i];
  argc = kept;
  benchmark::Initialize(&argc, argv);
  // No PETSc option is read here: anything left is a mistake, not an option.
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 2;
  if (case_path.empty()) {
    std::fprintf(stderr, "usage: %s --case=CASE.toml [benchmark options]\n", argv[0]);
    return 2;
  }
  la::PetscSession petsc(argc, argv);
  benchmark::AddCustomContext("processes", std::to_string(la::world_size()));
  benchmark::AddCustomContext("case", case_path);
  benchmark::RegisterBenchmark("Cut", cut)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(3);
  benchmark::RegisterBenchmark("Assemble", assemble)
      ->Arg(0)
      ->Arg(1)
      ->Arg(2)
      ->UseManualTime()
      ->Unit(benchmark::kMillisecond)
      ->Iterations(3);
  return bench::run_reported_by_process_zero();
}
