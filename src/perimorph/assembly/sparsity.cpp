#include "perimorph/assembly/sparsity.hpp"

#include "perimorph/dofs/dof_map.hpp"

#include <algorithm>

namespace perimorph::assembly {

SparsityPattern build_sparsity(const dofs::DofMap& dofmap, std::span<const std::pair<Index, Index>> extra_cell_pairs) {
  const auto n = static_cast<std::size_t>(dofmap.num_nodes());
  // Two passes over the couplings: count an upper bound, fill, then sort-unique.
  std::vector<Index> count(n + 1, 0);
  auto visit = [&](auto&& emit) {
    for (Index c = 0; c < dofmap.num_cells(); ++c)
      for (Index a : dofmap.cell_nodes(c))
        for (Index b : dofmap.cell_nodes(c)) emit(a, b);
    for (auto [e, f] : extra_cell_pairs)
      for (Index a : dofmap.cell_nodes(e))
        for (Index b : dofmap.cell_nodes(f)) {
          emit(a, b);
          emit(b, a);
        }
  };
  visit([&](Index a, Index) { ++count[static_cast<std::size_t>(a) + 1]; });
  std::vector<Index> start(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) start[i + 1] = start[i] + count[i + 1];
  std::vector<Index> raw(static_cast<std::size_t>(start[n]));
  std::vector<Index> fill(start.begin(), start.end() - 1);
  visit([&](Index a, Index b) { raw[static_cast<std::size_t>(fill[static_cast<std::size_t>(a)]++)] = b; });

  SparsityPattern pattern;
  pattern.block_size = dofmap.block_size();
  pattern.row_offsets.reserve(n + 1);
  pattern.row_offsets.push_back(0);
  for (std::size_t r = 0; r < n; ++r) {
    auto first = raw.begin() + start[r];
    auto last = raw.begin() + start[r + 1];
    std::sort(first, last);
    last = std::unique(first, last);
    pattern.columns.insert(pattern.columns.end(), first, last);
    pattern.row_offsets.push_back(static_cast<Index>(pattern.columns.size()));
  }
  return pattern;
}

}  // namespace perimorph::assembly
