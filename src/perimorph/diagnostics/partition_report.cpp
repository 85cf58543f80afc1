#include "perimorph/diagnostics/partition_report.hpp"

#include "perimorph/bonds/cell_graph.hpp"
#include "perimorph/la/graph_partition.hpp"
#include "perimorph/partition/partition.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
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
  return out;
}

}  // namespace perimorph::diagnostics
