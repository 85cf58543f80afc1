#pragma once
// What the model of a case holds in memory, stage by stage (issue 17, item
// 1): the figures `perimorph info` prints, and the weak-scaling model of
// docs/benchmarks/distributed-runs.md uses, for what every process of a
// distributed run holds whole and what it holds for its part only.

#include <cstddef>

namespace perimorph::setup {
struct Discretization;
}

namespace perimorph::diagnostics {

/// Bytes of each stage's arrays (their sizes, not their capacities).
struct ModelMemory {
  std::size_t mesh = 0;  ///< nodes, connectivity, regions, sets
  std::size_t dofs = 0;  ///< the dof map (cell nodes, CG/DG flags, each dof node's mesh node)
  std::size_t points =
      0;  ///< the stored non-local points (positions, weights, α, boxes; a part's, on a process)
  std::size_t cell_alpha = 0;  ///< the points' α bounds per cell and the stored cells' slots (whole)
  std::size_t graph = 0;  ///< the cell graph (one Index per directed cell pair; a part's rows, on a process)
  std::size_t flags = 0;  ///< the purely non-local flags (a byte a cell)
  std::size_t stiffness = 0;  ///< the morphed C (only the cells a part computes, on a process)
  /// On a process's piece of the model (setup::cut_to_piece): its maps to
  /// the whole model's numbers (cells, nodes, cell parts, dof keys and owners).
  std::size_t piece_maps = 0;
  /// What a run adds, whole on every process: the displacement u (a double
  /// a dof, filled at the halo) and the dof nodes' distributed numbers
  /// (la::Distribution, an Index a dof node).
  std::size_t displacement = 0;
  std::size_t distribution = 0;
  /// What every process of a distributed run holds whole today, of the model.
  std::size_t whole() const { return mesh + dofs + cell_alpha + flags; }
};

ModelMemory model_memory(const setup::Discretization& model);

}  // namespace perimorph::diagnostics
