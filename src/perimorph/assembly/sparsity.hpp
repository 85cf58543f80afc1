#pragma once
// The sparsity pattern, built from the same data assembly uses (STYLE.md
// habit 4): a graph between dof nodes (each carrying block_size components)
// given as compressed rows. PETSc preallocation from it is exact.

#include "perimorph/core/types.hpp"

#include <cassert>
#include <functional>
#include <span>
#include <vector>

namespace perimorph::dofs {
class DofMap;
}
namespace perimorph::bonds {
struct CellGraph;
}

namespace perimorph::assembly {

struct SparsityPattern {
  int block_size = 1;
  std::vector<Index> row_offsets;  ///< size num_block_rows + 1
  std::vector<Index> columns;      ///< sorted within each row, includes the diagonal
  Index num_block_rows() const { return static_cast<Index>(row_offsets.size()) - 1; }
  std::span<const Index> row(Index r) const {
    assert(r >= 0 && r < num_block_rows());
    return {columns.data() + row_offsets[static_cast<std::size_t>(r)],
            static_cast<std::size_t>(row_offsets[static_cast<std::size_t>(r) + 1] -
                                     row_offsets[static_cast<std::size_t>(r)])};
  }
};

/// Pattern coupling the dof nodes of every cell with themselves (local model)
/// and, if a cell graph is given, with the dof nodes of every neighbour cell
/// (non-local model). Built row by row with a marker array: memory is the
/// pattern itself. With `keep_row`, the rows of the dof nodes it accepts
/// only, the others empty: a process of a distributed run builds its owned
/// rows (la::Matrix reads no other), so the pattern's memory and work fall
/// with the number of processes.
SparsityPattern build_sparsity(const dofs::DofMap& dofmap, const bonds::CellGraph* graph = nullptr,
                               const std::function<bool(Index)>& keep_row = {});

}  // namespace perimorph::assembly
