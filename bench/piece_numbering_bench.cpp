// The dof numbering of a distributed run (issue 17, item 1;
// docs/benchmarks/distributed-runs.md, "A process's piece"): what each
// process does today, against what it does from its piece alone. Run under
// mpirun -n P (every process runs every benchmark the same number of times:
// the piece's numbering is collective).
//
//   Whole/n   partition::dof_numbering of the whole model's dof map (every
//             process, O(whole)): the owners and the distributed number of
//             every dof node of the model
//   Piece/n   from the cells of the process's piece (its part and their node
//             neighbours, listed outside the timed region): mesh::part_mesh,
//             the dof map on it, partition::piece_dofs and
//             system::piece_distribution (a prefix sum and an exchange of the
//             ghosts' numbers by key): the distributed number of the piece's
//             dof nodes only
//
// Model: a box of n × n × n/2 hexahedra, DG (degree 1) in a slab of n/10
// cells across y (a crack zone), CG elsewhere. Counters: cells and dof nodes
// the process holds numbers for, and the bytes of its numbering. Times:
// manual (each iteration starts at a barrier), ms.
// Run: mpirun -n 2 build/bench/piece_numbering_bench --benchmark_repetitions=3

#include "perimorph/dofs/dof_map.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/mesh/box.hpp"
#include "perimorph/mesh/part_mesh.hpp"
#include "perimorph/partition/dof_layout.hpp"
#include "perimorph/partition/piece_dofs.hpp"
#include "perimorph/system/piece_distribution.hpp"

#include "support/collective.hpp"

#include <benchmark/benchmark.h>

#include <map>
#include <memory>

namespace {

using namespace perimorph;

struct Model {
  mesh::Mesh mesh;
  std::vector<dofs::Continuity> flags;
  partition::Partition partition;
  std::vector<Index> piece_cells;
};

Model& model(int n) {
  static std::map<int, std::unique_ptr<Model>> cache;
  auto& m = cache[n];
  if (m) return *m;
  const auto nz = std::max(1, n / 2);
  auto mesh = mesh::make_box({3, Vec3(0, 0, 0), Vec3(n, n, nz), {n, n, nz}});
  std::vector<dofs::Continuity> flags(static_cast<std::size_t>(mesh.num_cells()),
                                      dofs::Continuity::continuous);
  for (Index c = 0; c < mesh.num_cells(); ++c)
    if (std::abs(mesh.cell_centroid(c)[1] - 0.5 * n) < 0.05 * n)
      flags[static_cast<std::size_t>(c)] = dofs::Continuity::discontinuous;
  auto p = partition::coordinate_bisection(mesh, la::world_size());
  std::vector<Index> cells;
  const auto near = partition::cells_near_part(mesh, p.parts, la::world_rank());
  for (Index c = 0; c < mesh.num_cells(); ++c)
    if (near.empty() || near[static_cast<std::size_t>(c)]) cells.push_back(c);
  m = std::make_unique<Model>(Model{std::move(mesh), std::move(flags), std::move(p), std::move(cells)});
  return *m;
}

void whole(benchmark::State& state) {
  const Model& m = model(static_cast<int>(state.range(0)));
  std::size_t nodes = 0;
  bench::time_collectively(state, [&] {
    const dofs::DofMap dm(m.mesh, 3, m.flags);
    const auto layout = partition::dof_numbering(dm, m.partition);
    nodes = layout.to_distributed.size();
    benchmark::DoNotOptimize(layout.to_distributed.data());
  });
  state.counters["cells"] = static_cast<double>(m.mesh.num_cells());
  state.counters["dof_nodes"] = static_cast<double>(nodes);
  state.counters["numbering_bytes"] = static_cast<double>(nodes * (sizeof(Index) + sizeof(int)));
}

void piece(benchmark::State& state) {
  const Model& m = model(static_cast<int>(state.range(0)));
  std::size_t nodes = 0;
  bench::time_collectively(state, [&] {
    const auto pm = mesh::part_mesh(m.mesh, m.piece_cells);
    std::vector<dofs::Continuity> flags;
    std::vector<int> owner;
    for (Index g : pm.global_cell) {
      flags.push_back(m.flags[static_cast<std::size_t>(g)]);
      owner.push_back(m.partition.owner[static_cast<std::size_t>(g)]);
    }
    const dofs::DofMap dm(pm.mesh, 3, flags);
    const auto d = system::piece_distribution(
        partition::piece_dofs(dm, pm, owner, la::world_rank(), m.mesh.num_nodes(), m.mesh.num_cells()));
    nodes = d->to_distributed.size();
    benchmark::DoNotOptimize(d->to_distributed.data());
  });
  state.counters["cells"] = static_cast<double>(m.piece_cells.size());
  state.counters["dof_nodes"] = static_cast<double>(nodes);
  state.counters["numbering_bytes"] = static_cast<double>(nodes * sizeof(Index));
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  // No PETSc option is read here: anything left is a mistake, not an option.
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 2;
  la::PetscSession petsc(argc, argv);
  benchmark::AddCustomContext("processes", std::to_string(la::world_size()));
  for (int n : {40, 80}) {
    benchmark::RegisterBenchmark("Whole", whole)
        ->Arg(n)
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond)
        ->Iterations(3);
    benchmark::RegisterBenchmark("Piece", piece)
        ->Arg(n)
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond)
        ->Iterations(3);
  }
  return bench::run_reported_by_process_zero();
}
