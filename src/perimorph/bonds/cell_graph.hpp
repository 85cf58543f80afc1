#pragma once
// Which cells interact non-locally: a symmetric cell graph in compressed rows
// (each row sorted, the cell itself included), found with cell lists (uniform
// bins of the cells' centroids), never an all-pairs loop (THEORY §4).
//
// Memory: the graph stores one Index per directed cell pair; bonds themselves
// are not stored — the assembly regenerates the quadrature-point pairs of a
// cell pair on the fly from NonlocalPoints (0 bytes per bond).

#include "perimorph/core/types.hpp"

#include <functional>
#include <span>
#include <vector>

namespace perimorph::mesh {
class Mesh;
}

namespace perimorph::bonds {

struct CellGraph {
  std::vector<Index> offsets;    ///< size num_cells + 1
  std::vector<Index> neighbors;  ///< sorted within each row

  Index num_cells() const { return static_cast<Index>(offsets.size()) - 1; }
  std::span<const Index> row(Index c) const {
    return {neighbors.data() + offsets[static_cast<std::size_t>(c)],
            static_cast<std::size_t>(offsets[static_cast<std::size_t>(c) + 1] -
                                     offsets[static_cast<std::size_t>(c)])};
  }
  /// Number of unordered pairs (E ≤ F).
  std::size_t num_pairs() const;
  /// The graph where every cell is its own only neighbour (a local model).
  static CellGraph diagonal(Index num_cells);
  /// The diagonal graph plus the given pairs, in both directions.
  static CellGraph from_pairs(Index num_cells, std::span<const std::pair<Index, Index>> pairs);
};

/// Pairs of cells whose closed bounding boxes (of their nodes) are closer than
/// `horizon`, kept only if `keep(E, F)` holds (all pairs if empty).
CellGraph find_cell_neighbors(const mesh::Mesh& mesh, double horizon,
                              const std::function<bool(Index, Index)>& keep = {});

}  // namespace perimorph::bonds
