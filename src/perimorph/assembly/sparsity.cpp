#include "perimorph/assembly/sparsity.hpp"

#include "perimorph/bonds/cell_graph.hpp"
#include "perimorph/dofs/dof_map.hpp"

#include <algorithm>

namespace perimorph::assembly {

SparsityPattern build_sparsity(const dofs::DofMap& dofmap, const bonds::CellGraph* graph,
                               const std::function<bool(Index)>& keep_row) {
  const auto nnodes = static_cast<std::size_t>(dofmap.num_nodes());
  const Index ncells = dofmap.num_cells();
  std::vector<char> kept(nnodes, 1);
  if (keep_row)
    for (std::size_t a = 0; a < nnodes; ++a) kept[a] = keep_row(static_cast<Index>(a)) ? 1 : 0;
  // Cells touching each kept dof node.
  std::vector<Index> start(nnodes + 1, 0);
  for (Index c = 0; c < ncells; ++c)
    for (Index n : dofmap.cell_nodes(c))
      if (kept[static_cast<std::size_t>(n)]) ++start[static_cast<std::size_t>(n) + 1];
  for (std::size_t i = 0; i < nnodes; ++i) start[i + 1] += start[i];
  std::vector<Index> node_cells(static_cast<std::size_t>(start[nnodes]));
  {
    std::vector<Index> fill(start.begin(), start.end() - 1);
    for (Index c = 0; c < ncells; ++c)
      for (Index n : dofmap.cell_nodes(c))
        if (kept[static_cast<std::size_t>(n)])
          node_cells[static_cast<std::size_t>(fill[static_cast<std::size_t>(n)]++)] = c;
  }

  std::vector<std::vector<Index>> rows(nnodes);
#pragma omp parallel
  {
    std::vector<char> mark(nnodes, 0);
#pragma omp for schedule(dynamic, 256)
    for (std::size_t a = 0; a < nnodes; ++a) {
      auto& row = rows[a];
      auto add_cell = [&](Index f) {
        for (Index b : dofmap.cell_nodes(f))
          if (!mark[static_cast<std::size_t>(b)]) {
            mark[static_cast<std::size_t>(b)] = 1;
            row.push_back(b);
          }
      };
      for (Index k = start[a]; k < start[a + 1]; ++k) {
        const Index c = node_cells[static_cast<std::size_t>(k)];
        add_cell(c);
        if (graph)
          for (Index f : graph->row(c)) add_cell(f);
      }
      for (Index b : row) mark[static_cast<std::size_t>(b)] = 0;
      std::sort(row.begin(), row.end());
    }
  }

  SparsityPattern pattern;
  pattern.block_size = dofmap.block_size();
  pattern.row_offsets.reserve(nnodes + 1);
  pattern.row_offsets.push_back(0);
  std::size_t total = 0;
  for (const auto& r : rows) total += r.size();
  pattern.columns.reserve(total);
  for (auto& r : rows) {
    pattern.columns.insert(pattern.columns.end(), r.begin(), r.end());
    pattern.row_offsets.push_back(static_cast<Index>(pattern.columns.size()));
    std::vector<Index>().swap(r);
  }
  return pattern;
}

}  // namespace perimorph::assembly
