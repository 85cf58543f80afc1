#include "perimorph/diagnostics/partition_report.hpp"

#include "perimorph/bonds/cell_graph.hpp"
#include "perimorph/la/graph_partition.hpp"
#include "perimorph/partition/dof_layout.hpp"
#include "perimorph/partition/grid_bisection.hpp"
#include "perimorph/partition/partition.hpp"
#include "perimorph/setup/mesh_window.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <string>
#include <vector>

namespace perimorph::diagnostics {

std::string partition_report(const setup::Discretization& disc, int parts) {
  const bonds::CellGraph diagonal = bonds::CellGraph::diagonal(disc.mesh.num_cells());
  const bonds::CellGraph graph =
      partition::coupling_graph(disc.mesh, disc.nonlocal ? disc.nonlocal->graph : diagonal);
  std::string out = fmt::format(
      "partition  {} parts of {} cells; halo: cells of other parts that share a node with an owned cell or "
      "interact with one ({} coupled cell pairs)\n",
      parts, disc.mesh.num_cells(), graph.num_pairs());
  out += fmt::format("           {:<22} {:>10} {:>10} {:>11} {:>10} {:>10} {:>8}\n", "partitioner",
                     "max owned", "max halo", "halo/owned", "max nbrs", "pairs cut", "time [s]");
  auto row = [&](const char* name, auto make) {
    const auto t0 = std::chrono::steady_clock::now();
    const partition::Partition p = make();
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const auto h = partition::halo(graph, p);
    const int nbrs = h.neighbours.empty() ? 0 : *std::max_element(h.neighbours.begin(), h.neighbours.end());
    out += fmt::format(
        "           {:<22} {:>10} {:>10} {:>11.3f} {:>10} {:>9.2f}% {:>8.2f}\n", name, h.max_owned(),
        h.max_ghosts(), h.ghost_ratio(), nbrs,
        h.pairs ? 100.0 * static_cast<double>(h.cut_pairs) / static_cast<double>(h.pairs) : 0.0, t);
  };
  row("coordinate bisection", [&] { return partition::coordinate_bisection(disc.mesh, parts); });
  // The bisection's row has checked `parts` (1 … cells).
  row("PT-Scotch", [&] {
    return partition::Partition{
        parts, parts > 1 ? la::partition_graph(graph.offsets, graph.neighbors, parts, "ptscotch")
                         : std::vector<int>(static_cast<std::size_t>(disc.mesh.num_cells()), 0)};
  });
  // What a distributed run does with the bisection (owner computes,
  // partition/dof_layout.hpp): each part computes the cells and pairs that
  // touch its nodes, those touching two parts twice.
  const partition::Partition p = partition::coordinate_bisection(disc.mesh, parts);
  const bonds::CellGraph& bonds_graph = disc.nonlocal ? disc.nonlocal->graph : diagonal;
  const partition::DofLayout layout = partition::dof_layout(disc.dofmap, p, bonds_graph);
  Index max_owned = 0, max_ghosts = 0, max_received = 0, max_received_whole = 0;
  std::size_t cells_computed = 0, pairs_computed = 0, cells_morphed = 0, graph_entries = 0, point_cells = 0;
  for (int q = 0; q < parts; ++q) {
    const std::vector<char> near = partition::cells_near_part(disc.mesh, parts, q);
    std::size_t entries = 0;  // the graph rows the part holds (setup::Discretization::computed_cells)
    for (Index c = 0; c < disc.mesh.num_cells(); ++c)
      if (near[static_cast<std::size_t>(c)]) {
        ++cells_morphed;
        entries += bonds_graph.row(c).size();
      }
    graph_entries = std::max(graph_entries, entries);
    const std::vector<char> read = bonds_graph.cells_in_rows(near);  // whose points the part stores
    point_cells = std::max(point_cells, static_cast<std::size_t>(std::count(read.begin(), read.end(), 1)));
    max_owned = std::max(max_owned, layout.owned_nodes(q));
    // u after each solve (setup::nodes_read): the nodes of the cells whose
    // points the part stores (its computed cells without [nonlocal]), less
    // those it owns; gathered whole, every node it does not own.
    std::vector<Index> read_cells;
    for (Index c = 0; c < disc.mesh.num_cells(); ++c)
      if (disc.nonlocal ? read[static_cast<std::size_t>(c)] : near[static_cast<std::size_t>(c)])
        read_cells.push_back(c);
    Index received = 0;
    for (Index n : disc.dofmap.dof_nodes_of_cells(read_cells))
      received += layout.node_owner[static_cast<std::size_t>(n)] != q;
    max_received = std::max(max_received, received);
    max_received_whole = std::max(max_received_whole, disc.dofmap.num_nodes() - layout.owned_nodes(q));
    max_ghosts = std::max(max_ghosts, static_cast<Index>(layout.ghosts[static_cast<std::size_t>(q)].size()));
    const auto touching = partition::cells_touching(
        disc.dofmap, [&](Index n) { return layout.node_owner[static_cast<std::size_t>(n)] == q; });
    for (Index e = 0; e < disc.mesh.num_cells(); ++e) {
      const bool te = touching[static_cast<std::size_t>(e)] != 0;
      cells_computed += te;
      for (Index f : bonds_graph.row(e))
        if (f >= e && (te || touching[static_cast<std::size_t>(f)] != 0)) ++pairs_computed;
    }
  }
  const auto per = [](std::size_t a, std::size_t b) {
    return b ? static_cast<double>(a) / static_cast<double>(b) : 0.0;
  };
  out += fmt::format(
      "           owner computes (coordinate bisection): max owned dof nodes {}, max ghost nodes {} "
      "(ghosts/owned {:.3f}); cells computed {:.3f}× and cell pairs {:.3f}× those of one process{}\n",
      max_owned, max_ghosts, layout.ghost_ratio(),
      per(cells_computed, static_cast<std::size_t>(disc.mesh.num_cells())),
      per(pairs_computed, bonds_graph.num_pairs()),
      disc.nonlocal && parts > 1
          ? fmt::format("; morphed C set up for {:.3f}× the cells (each part's and their node neighbours), "
                        "and their cell graph rows held: the largest part {:.3f} of the whole graph, and "
                        "the non-local points of {:.3f} of the cells",
                        per(cells_morphed, static_cast<std::size_t>(disc.mesh.num_cells())),
                        per(graph_entries, bonds_graph.neighbors.size()),
                        per(point_cells, static_cast<std::size_t>(disc.mesh.num_cells())))
          : std::string());
  if (parts > 1)
    out += fmt::format(
        "           u after each solve: the largest part receives {} of the {} dof nodes ({:.3f}; "
        "gathered whole: {}, {:.3f})\n",
        max_received, disc.dofmap.num_nodes(),
        per(static_cast<std::size_t>(max_received), static_cast<std::size_t>(disc.dofmap.num_nodes())),
        max_received_whole,
        per(static_cast<std::size_t>(max_received_whole), static_cast<std::size_t>(disc.dofmap.num_nodes())));
  if (parts > 1 && setup::has_windows(disc.config)) {
    // What a distributed run builds its parts on (setup::part_window).
    const auto t0 = std::chrono::steady_clock::now();
    const partition::GridBisection grid = setup::grid_bisection(disc.config, parts);
    std::size_t largest = 0;
    for (int q = 0; q < parts; ++q)
      largest = std::max(largest, setup::part_window(disc.config, grid, q).owner.size());
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    out += fmt::format(
        "           set-up on windows of the box: the largest part's window holds {} of the {} cells "
        "({:.3f}), "
        "the length of its set-up's mesh, dof map, alpha bounds and flags ({:.2f} s to find every part's)\n",
        largest, disc.mesh.num_cells(), per(largest, static_cast<std::size_t>(disc.mesh.num_cells())), t);
  }
  return out;
}

}  // namespace perimorph::diagnostics
