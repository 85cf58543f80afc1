#include "perimorph/partition/partition.hpp"

#include "perimorph/bonds/cell_graph.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/mesh/mesh.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <numeric>

namespace perimorph::partition {

namespace {

/// Assigns parts [first, first + q) to `cells` (centroids `x`), recursively.
void bisect(std::vector<Index>& cells, std::size_t lo, std::size_t hi, int first, int q,
            const std::vector<Vec3>& x, int dim, std::vector<int>& owner) {
  if (q == 1) {
    for (std::size_t k = lo; k < hi; ++k) owner[static_cast<std::size_t>(cells[k])] = first;
    return;
  }
  Vec3 a = Vec3::Constant(std::numeric_limits<double>::infinity()), b = -a;
  for (std::size_t k = lo; k < hi; ++k) {
    a = a.cwiseMin(x[static_cast<std::size_t>(cells[k])]);
    b = b.cwiseMax(x[static_cast<std::size_t>(cells[k])]);
  }
  int axis = 0;
  for (int d = 1; d < dim; ++d)
    if (b[d] - a[d] > b[axis] - a[axis]) axis = d;
  const int q1 = q / 2;
  const std::size_t n = hi - lo;
  const std::size_t n1 =
      (n * static_cast<std::size_t>(q1) + static_cast<std::size_t>(q) / 2) / static_cast<std::size_t>(q);
  const auto begin = cells.begin() + static_cast<std::ptrdiff_t>(lo);
  std::nth_element(begin, begin + static_cast<std::ptrdiff_t>(n1),
                   cells.begin() + static_cast<std::ptrdiff_t>(hi), [&](Index i, Index j) {
                     const double xi = x[static_cast<std::size_t>(i)][axis],
                                  xj = x[static_cast<std::size_t>(j)][axis];
                     return xi < xj || (xi == xj && i < j);
                   });
  bisect(cells, lo, lo + n1, first, q1, x, dim, owner);
  bisect(cells, lo + n1, hi, first + q1, q - q1, x, dim, owner);
}

}  // namespace

std::vector<char> cells_of_part(const mesh::Mesh& mesh, int parts, int part) {
  if (parts == 1) return {};
  const Partition p = coordinate_bisection(mesh, parts);
  std::vector<char> mine(p.owner.size(), 0);
  for (std::size_t c = 0; c < p.owner.size(); ++c) mine[c] = p.owner[c] == part ? 1 : 0;
  return mine;
}

std::vector<char> cells_near_part(const mesh::Mesh& mesh, int parts, int part) {
  if (parts == 1) return {};
  return cells_near_part(mesh, coordinate_bisection(mesh, parts).owner, part);
}

std::vector<char> cells_near_part(const mesh::Mesh& mesh, std::span<const int> owner, int part) {
  PERIMORPH_ASSERT(static_cast<Index>(owner.size()) == mesh.num_cells(), "a part for every cell");
  std::vector<char> near(owner.size(), 0);
  for (std::size_t c = 0; c < owner.size(); ++c) near[c] = owner[c] == part ? 1 : 0;
  std::vector<char> node_of_part(static_cast<std::size_t>(mesh.num_nodes()), 0);
  for (Index c = 0; c < mesh.num_cells(); ++c)
    if (near[static_cast<std::size_t>(c)])
      for (Index n : mesh.cell(c)) node_of_part[static_cast<std::size_t>(n)] = 1;
  for (Index c = 0; c < mesh.num_cells(); ++c)
    for (Index n : mesh.cell(c))
      if (node_of_part[static_cast<std::size_t>(n)]) near[static_cast<std::size_t>(c)] = 1;
  return near;
}

Partition coordinate_bisection(const mesh::Mesh& mesh, int parts) {
  const Index n = mesh.num_cells();
  if (parts < 1 || parts > n)
    throw InputError(fmt::format("cannot partition {} cells into {} parts: give 1 to {} parts", n, parts, n));
  std::vector<Vec3> x(static_cast<std::size_t>(n));
  for (Index c = 0; c < n; ++c) x[static_cast<std::size_t>(c)] = mesh.cell_centroid(c);
  std::vector<Index> cells(static_cast<std::size_t>(n));
  std::iota(cells.begin(), cells.end(), Index{0});
  Partition p{parts, std::vector<int>(static_cast<std::size_t>(n), 0)};
  bisect(cells, 0, cells.size(), 0, parts, x, mesh.dim(), p.owner);
  return p;
}

Index HaloStats::max_owned() const {
  return owned.empty() ? 0 : *std::max_element(owned.begin(), owned.end());
}
Index HaloStats::max_ghosts() const {
  return ghosts.empty() ? 0 : *std::max_element(ghosts.begin(), ghosts.end());
}
double HaloStats::ghost_ratio() const {
  const double o = static_cast<double>(std::accumulate(owned.begin(), owned.end(), Index{0}));
  return o > 0 ? static_cast<double>(std::accumulate(ghosts.begin(), ghosts.end(), Index{0})) / o : 0.0;
}

bonds::CellGraph coupling_graph(const mesh::Mesh& mesh, const bonds::CellGraph& graph) {
  const Index n = mesh.num_cells();
  PERIMORPH_ASSERT(graph.num_cells() == n, "the cell graph must be of the mesh");
  // Cells of each node (compressed rows).
  std::vector<Index> start(static_cast<std::size_t>(mesh.num_nodes()) + 1, 0), cells_of;
  for (Index c = 0; c < n; ++c)
    for (Index v : mesh.cell(c)) ++start[static_cast<std::size_t>(v) + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  cells_of.resize(static_cast<std::size_t>(start.back()));
  std::vector<Index> fill(start.begin(), start.end() - 1);
  for (Index c = 0; c < n; ++c)
    for (Index v : mesh.cell(c)) cells_of[static_cast<std::size_t>(fill[static_cast<std::size_t>(v)]++)] = c;
  bonds::CellGraph out;
  out.offsets.assign(1, 0);
  std::vector<Index> row;
  for (Index c = 0; c < n; ++c) {
    const auto g = graph.row(c);
    row.assign(g.begin(), g.end());
    row.push_back(c);
    for (Index v : mesh.cell(c))
      row.insert(row.end(), cells_of.begin() + start[static_cast<std::size_t>(v)],
                 cells_of.begin() + start[static_cast<std::size_t>(v) + 1]);
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
    out.neighbors.insert(out.neighbors.end(), row.begin(), row.end());
    out.offsets.push_back(static_cast<Index>(out.neighbors.size()));
  }
  return out;
}

HaloStats halo(const bonds::CellGraph& coupling, const Partition& p) {
  const Index n = coupling.num_cells();
  PERIMORPH_ASSERT(static_cast<Index>(p.owner.size()) == n, "the partition must be of the graph's cells");
  const auto P = static_cast<std::size_t>(p.parts);
  HaloStats s;
  s.owned.assign(P, 0);
  s.ghosts.assign(P, 0);
  s.neighbours.assign(P, 0);
  std::vector<std::vector<Index>> members(P);
  for (Index c = 0; c < n; ++c) {
    const auto o = static_cast<std::size_t>(p.owner[static_cast<std::size_t>(c)]);
    ++s.owned[o];
    members[o].push_back(c);
  }
  // stamp = part + 1: a cell (or part) already counted for this part.
  std::vector<std::size_t> stamp(static_cast<std::size_t>(n), 0), part_stamp(P, 0);
  for (std::size_t q = 0; q < P; ++q)
    for (Index c : members[q])
      for (Index d : coupling.row(c)) {
        const auto od = static_cast<std::size_t>(p.owner[static_cast<std::size_t>(d)]);
        if (od == q || stamp[static_cast<std::size_t>(d)] == q + 1) continue;
        stamp[static_cast<std::size_t>(d)] = q + 1;
        ++s.ghosts[q];
        if (part_stamp[od] != q + 1) {
          part_stamp[od] = q + 1;
          ++s.neighbours[q];
        }
      }
  for (Index c = 0; c < n; ++c)
    for (Index d : coupling.row(c))
      if (c < d) {
        ++s.pairs;
        if (p.owner[static_cast<std::size_t>(c)] != p.owner[static_cast<std::size_t>(d)]) ++s.cut_pairs;
      }
  return s;
}

}  // namespace perimorph::partition
