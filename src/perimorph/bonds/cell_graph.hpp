#pragma once
// Which cells interact non-locally: a symmetric cell graph in compressed rows
// (each row sorted, the cell itself included), found with cell lists (uniform
// bins of the cells' centroids), never an all-pairs loop (THEORY §4).
//
// Memory: the graph stores one Index per directed cell pair; bonds themselves
// are not stored — the assembly regenerates the quadrature-point pairs of a
// cell pair on the fly from NonlocalPoints (0 bytes per bond).

#include "perimorph/core/types.hpp"

#include <cassert>
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
    assert(c >= 0 && c < num_cells());
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
  /// The rows of the flagged cells (one flag per cell), the others empty: what
  /// a process of a distributed run needs of the graph (issue 17); a reader of
  /// only the flagged rows gets the same from it as from the whole graph.
  CellGraph rows_of(std::span<const char> cells) const;
  /// The rows of the listed cells (ascending, each once), renumbered: cell k
  /// of the result is cells[k], and so are the neighbours. A process's piece
  /// of a model (setup::cut_to_piece). Throws Error for a neighbour not
  /// listed.
  CellGraph renumbered(std::span<const Index> cells) const;
  /// The flagged cells and every cell in their rows (one flag per cell): the
  /// cells whose non-local points a reader of those rows needs.
  std::vector<char> cells_in_rows(std::span<const char> cells) const;
};

/// One axis-aligned box per cell (lo, hi) containing every point of the cell
/// that can carry a bond.
struct CellBoxes {
  std::vector<Vec3> lo, hi;
};

/// The boxes of the cells' nodes (the whole cells).
CellBoxes node_boxes(const mesh::Mesh& mesh);

/// The boxes of the cells' quadrature points: the images of the reference
/// points (Q1 map) of every rule given, so a box covers the local and the
/// non-local points. Tighter than node_boxes: Gauss points stay inside.
CellBoxes point_boxes(const mesh::Mesh& mesh, std::span<const Vec3> reference_points);

/// Pairs of cells whose closed boxes are closer than `reach` (the largest
/// separation that carries a bond), kept only if `keep(E, F)` holds (all pairs
/// if empty). Cell lists on the boxes' centres: no all-pairs loop. With
/// `rows` (one flag per cell), the rows of the flagged cells only, the others
/// empty (CellGraph::rows_of of the whole graph, without building it).
CellGraph find_cell_neighbors(const mesh::Mesh& mesh, const CellBoxes& boxes, double reach,
                              const std::function<bool(Index, Index)>& keep = {},
                              std::span<const char> rows = {});

/// The same with node_boxes.
CellGraph find_cell_neighbors(const mesh::Mesh& mesh, double reach,
                              const std::function<bool(Index, Index)>& keep = {});

}  // namespace perimorph::bonds
