#include "perimorph/partition/dof_layout.hpp"

#include "perimorph/bonds/cell_graph.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/dofs/dof_map.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <numeric>

namespace perimorph::partition {

double DofLayout::ghost_ratio() const {
  std::size_t ghost_nodes = 0;
  for (const auto& g : ghosts) ghost_nodes += g.size();
  return num_nodes() > 0 ? static_cast<double>(ghost_nodes) / static_cast<double>(num_nodes()) : 0.0;
}

DofLayout dof_numbering(const dofs::DofMap& dofmap, const Partition& p) {
  const Index cells = dofmap.num_cells();
  if (static_cast<Index>(p.owner.size()) != cells)
    throw Error(fmt::format("dof layout: the partition has {} cells, the dof map {}", p.owner.size(), cells));
  const auto parts = static_cast<std::size_t>(p.parts);
  DofLayout out;
  out.parts = p.parts;
  const auto nodes = static_cast<std::size_t>(dofmap.num_nodes());

  // The lowest part among the cells touching a node (a DG node touches one cell).
  out.node_owner.assign(nodes, p.parts);
  for (Index c = 0; c < cells; ++c) {
    const int owner = p.owner[static_cast<std::size_t>(c)];
    if (owner < 0 || owner >= p.parts)
      throw Error(
          fmt::format("dof layout: cell {} has owner {}, not one of the {} parts", c, owner, p.parts));
    for (Index n : dofmap.cell_nodes(c)) {
      int& o = out.node_owner[static_cast<std::size_t>(n)];
      o = std::min(o, owner);
    }
  }
  // A node of no cell (a mesh vertex a hole left behind) has no stiffness to
  // assemble; part 0 keeps it.
  for (int& o : out.node_owner)
    if (o == p.parts) o = 0;

  // Counting sort by owner, serial order within a part.
  out.part_offsets.assign(parts + 1, 0);
  for (int o : out.node_owner) ++out.part_offsets[static_cast<std::size_t>(o) + 1];
  std::partial_sum(out.part_offsets.begin(), out.part_offsets.end(), out.part_offsets.begin());
  std::vector<Index> next(out.part_offsets.begin(), out.part_offsets.end() - 1);
  out.to_distributed.resize(nodes);
  for (std::size_t n = 0; n < nodes; ++n)
    out.to_distributed[n] = next[static_cast<std::size_t>(out.node_owner[n])]++;
  return out;
}

DofLayout dof_layout(const dofs::DofMap& dofmap, const Partition& p, const bonds::CellGraph& graph) {
  const Index cells = dofmap.num_cells();
  if (graph.num_cells() != cells)
    throw Error(
        fmt::format("dof layout: the cell graph has {} cells, the dof map {}", graph.num_cells(), cells));
  DofLayout out = dof_numbering(dofmap, p);
  const auto parts = static_cast<std::size_t>(p.parts);
  const auto nodes = static_cast<std::size_t>(dofmap.num_nodes());

  // Ghosts: the nodes of the cells a part computes (touching an owned node)
  // and of their neighbours in the cell graph, owned by another part.
  out.ghosts.assign(parts, {});
  std::vector<int> marked(nodes, -1);
  for (std::size_t part = 0; part < parts; ++part) {
    auto& ghosts = out.ghosts[part];
    const auto touching = cells_touching(dofmap, [&](Index n) {
      return out.node_owner[static_cast<std::size_t>(n)] == static_cast<int>(part);
    });
    const auto mark_cell = [&](Index c) {
      for (Index n : dofmap.cell_nodes(c)) {
        const auto k = static_cast<std::size_t>(n);
        if (marked[k] == static_cast<int>(part)) continue;
        marked[k] = static_cast<int>(part);
        if (out.node_owner[k] != static_cast<int>(part)) ghosts.push_back(n);
      }
    };
    for (Index e = 0; e < cells; ++e) {
      if (!touching[static_cast<std::size_t>(e)]) continue;
      mark_cell(e);
      for (Index f : graph.row(e)) mark_cell(f);
    }
    std::sort(ghosts.begin(), ghosts.end());
  }
  return out;
}

}  // namespace perimorph::partition
