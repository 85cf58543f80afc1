#pragma once
// The sparsity pattern, built from the same data assembly uses (STYLE.md
// habit 4): a graph between dof nodes (each carrying block_size components)
// given as compressed rows. PETSc preallocation from it is exact.

#include "perimorph/core/types.hpp"

#include <span>
#include <vector>

namespace perimorph::dofs {
class DofMap;
}

namespace perimorph::assembly {

struct SparsityPattern {
  int block_size = 1;
  std::vector<Index> row_offsets;  ///< size num_block_rows + 1
  std::vector<Index> columns;      ///< sorted within each row, includes the diagonal
  Index num_block_rows() const { return static_cast<Index>(row_offsets.size()) - 1; }
  std::span<const Index> row(Index r) const {
    return {columns.data() + row_offsets[static_cast<std::size_t>(r)],
            static_cast<std::size_t>(row_offsets[static_cast<std::size_t>(r) + 1] - row_offsets[static_cast<std::size_t>(r)])};
  }
};

/// Pattern of the blocks coupling the dof nodes of cell pairs (c, c) for every
/// cell, plus (a, b) for every extra pair given (non-local coupling, both
/// directions added).
SparsityPattern build_sparsity(const dofs::DofMap& dofmap, std::span<const std::pair<Index, Index>> extra_cell_pairs = {});

}  // namespace perimorph::assembly
