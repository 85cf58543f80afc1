#include "perimorph/bonds/cell_graph.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/mesh/mesh.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace perimorph::bonds {

CellGraph CellGraph::diagonal(Index num_cells) {
  CellGraph g;
  g.offsets.resize(static_cast<std::size_t>(num_cells) + 1);
  g.neighbors.resize(static_cast<std::size_t>(num_cells));
  for (Index c = 0; c <= num_cells; ++c) g.offsets[static_cast<std::size_t>(c)] = c;
  for (Index c = 0; c < num_cells; ++c) g.neighbors[static_cast<std::size_t>(c)] = c;
  return g;
}

CellGraph CellGraph::from_pairs(Index num_cells, std::span<const std::pair<Index, Index>> pairs) {
  std::vector<std::vector<Index>> rows(static_cast<std::size_t>(num_cells));
  for (Index c = 0; c < num_cells; ++c) rows[static_cast<std::size_t>(c)].push_back(c);
  for (auto [e, f] : pairs) {
    rows[static_cast<std::size_t>(e)].push_back(f);
    rows[static_cast<std::size_t>(f)].push_back(e);
  }
  CellGraph g;
  g.offsets.push_back(0);
  for (auto& row : rows) {
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
    g.neighbors.insert(g.neighbors.end(), row.begin(), row.end());
    g.offsets.push_back(static_cast<Index>(g.neighbors.size()));
  }
  return g;
}

CellGraph CellGraph::rows_of(std::span<const char> cells) const {
  assert(static_cast<Index>(cells.size()) == num_cells());
  CellGraph g;
  g.offsets.assign(offsets.size(), 0);
  for (Index c = 0; c < num_cells(); ++c) {
    if (cells[static_cast<std::size_t>(c)] != 0) {
      const auto r = row(c);
      g.neighbors.insert(g.neighbors.end(), r.begin(), r.end());
    }
    g.offsets[static_cast<std::size_t>(c) + 1] = static_cast<Index>(g.neighbors.size());
  }
  return g;
}

CellGraph CellGraph::renumbered(std::span<const Index> cells) const {
  PERIMORPH_ASSERT(std::is_sorted(cells.begin(), cells.end()), "renumbered: cells in ascending order");
  CellGraph g;
  g.offsets.reserve(cells.size() + 1);
  g.offsets.push_back(0);
  for (Index c : cells) {
    for (Index f : row(c)) {
      const auto it = std::lower_bound(cells.begin(), cells.end(), f);
      if (it == cells.end() || *it != f)
        throw Error(
            fmt::format("cell graph: cell {} in the row of cell {} is not among the listed cells", f, c));
      g.neighbors.push_back(static_cast<Index>(it - cells.begin()));  // ascending: the rows stay sorted
    }
    g.offsets.push_back(static_cast<Index>(g.neighbors.size()));
  }
  return g;
}

std::vector<char> CellGraph::cells_in_rows(std::span<const char> cells) const {
  assert(static_cast<Index>(cells.size()) == num_cells());
  std::vector<char> out(cells.begin(), cells.end());
  for (Index c = 0; c < num_cells(); ++c)
    if (cells[static_cast<std::size_t>(c)] != 0)
      for (Index f : row(c)) out[static_cast<std::size_t>(f)] = 1;
  return out;
}

std::size_t CellGraph::num_pairs() const {
  std::size_t n = 0;
  for (Index e = 0; e < num_cells(); ++e)
    for (Index f : row(e)) n += f >= e ? 1 : 0;
  return n;
}

CellBoxes node_boxes(const mesh::Mesh& mesh) {
  const Index ncells = mesh.num_cells();
  CellBoxes b;
  b.lo.assign(static_cast<std::size_t>(ncells), Vec3::Constant(std::numeric_limits<double>::max()));
  b.hi.assign(static_cast<std::size_t>(ncells), Vec3::Constant(std::numeric_limits<double>::lowest()));
  for (Index c = 0; c < ncells; ++c)
    for (Index n : mesh.cell(c)) {
      const Vec3& x = mesh.node(n);
      for (int d = 0; d < 3; ++d) {
        b.lo[static_cast<std::size_t>(c)][d] = std::min(b.lo[static_cast<std::size_t>(c)][d], x[d]);
        b.hi[static_cast<std::size_t>(c)][d] = std::max(b.hi[static_cast<std::size_t>(c)][d], x[d]);
      }
    }
  return b;
}

CellBoxes point_boxes(const mesh::Mesh& mesh, std::span<const Vec3> reference_points) {
  const Index ncells = mesh.num_cells();
  const int dim = mesh.dim();
  CellBoxes b;
  b.lo.assign(static_cast<std::size_t>(ncells), Vec3::Zero());
  b.hi.assign(static_cast<std::size_t>(ncells), Vec3::Zero());
  for (Index c = 0; c < ncells; ++c) {
    const auto nodes = mesh.cell(c);
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::max());
    Vec3 hi = Vec3::Constant(std::numeric_limits<double>::lowest());
    for (const Vec3& xi : reference_points) {
      Vec3 x = Vec3::Zero();
      for (int a = 0; a < mesh.nodes_per_cell(); ++a) {
        double N = 1.0;
        for (int d = 0; d < dim; ++d) N *= 0.5 * (1.0 + mesh::reference_node_coordinate(a, d) * xi[d]);
        x += N * mesh.node(nodes[static_cast<std::size_t>(a)]);
      }
      for (int d = 0; d < 3; ++d) {
        lo[d] = std::min(lo[d], x[d]);
        hi[d] = std::max(hi[d], x[d]);
      }
    }
    b.lo[static_cast<std::size_t>(c)] = lo;
    b.hi[static_cast<std::size_t>(c)] = hi;
  }
  return b;
}

CellGraph find_cell_neighbors(const mesh::Mesh& mesh, double reach,
                              const std::function<bool(Index, Index)>& keep) {
  return find_cell_neighbors(mesh, node_boxes(mesh), reach, keep);
}

CellGraph find_cell_neighbors(const mesh::Mesh& mesh, const CellBoxes& boxes, double reach,
                              const std::function<bool(Index, Index)>& keep,
                              std::span<const char> rows_wanted) {
  const int dim = mesh.dim();
  const Index ncells = mesh.num_cells();
  PERIMORPH_ASSERT(boxes.lo.size() == static_cast<std::size_t>(ncells) && boxes.hi.size() == boxes.lo.size(),
                   "one box per cell");
  PERIMORPH_ASSERT(rows_wanted.empty() || rows_wanted.size() == boxes.lo.size(), "one row flag per cell");
  const auto& lo = boxes.lo;
  const auto& hi = boxes.hi;
  const double horizon = reach;
  double extent = 0.0;
  for (Index c = 0; c < ncells; ++c)
    for (int d = 0; d < dim; ++d)
      extent = std::max(extent, hi[static_cast<std::size_t>(c)][d] - lo[static_cast<std::size_t>(c)][d]);
  // Bins of size ≥ horizon + extent: interacting cells have centroids in
  // adjacent bins.
  const double bin = horizon + extent;
  const auto box = mesh.bounding_box();
  const Vec3 box_lo = box.first,
             box_hi = box.second;  // (a lambda below uses them: clang < 16 cannot capture bindings)
  std::array<long, 3> nbins{1, 1, 1};
  for (int d = 0; d < dim; ++d)
    nbins[static_cast<std::size_t>(d)] =
        std::max(1L, static_cast<long>(std::floor((box_hi[d] - box_lo[d]) / bin)) + 1);
  auto bin_of = [&](const Vec3& x, int d) {
    return std::clamp(static_cast<long>(std::floor((x[d] - box_lo[d]) / bin)), 0L,
                      nbins[static_cast<std::size_t>(d)] - 1);
  };
  std::unordered_map<long, std::vector<Index>> bins;
  std::vector<std::array<long, 3>> cell_bin(static_cast<std::size_t>(ncells));
  for (Index c = 0; c < ncells; ++c) {
    const Vec3 centre = 0.5 * (lo[static_cast<std::size_t>(c)] + hi[static_cast<std::size_t>(c)]);
    std::array<long, 3> b{0, 0, 0};
    for (int d = 0; d < dim; ++d) b[static_cast<std::size_t>(d)] = bin_of(centre, d);
    cell_bin[static_cast<std::size_t>(c)] = b;
    bins[b[0] + nbins[0] * (b[1] + nbins[1] * b[2])].push_back(c);
  }

  auto close = [&](Index e, Index f) {
    double d2 = 0.0;
    for (int d = 0; d < dim; ++d) {
      const double gap =
          std::max({lo[static_cast<std::size_t>(f)][d] - hi[static_cast<std::size_t>(e)][d],
                    lo[static_cast<std::size_t>(e)][d] - hi[static_cast<std::size_t>(f)][d], 0.0});
      d2 += gap * gap;
    }
    return d2 < horizon * horizon;
  };

  std::vector<std::vector<Index>> rows(static_cast<std::size_t>(ncells));
#pragma omp parallel for schedule(dynamic, 64)
  for (Index e = 0; e < ncells; ++e) {
    if (!rows_wanted.empty() && rows_wanted[static_cast<std::size_t>(e)] == 0) continue;
    const auto b = cell_bin[static_cast<std::size_t>(e)];
    auto& row = rows[static_cast<std::size_t>(e)];
    for (long k = (dim > 2 ? -1 : 0); k <= (dim > 2 ? 1 : 0); ++k)
      for (long j = (dim > 1 ? -1 : 0); j <= (dim > 1 ? 1 : 0); ++j)
        for (long i = -1; i <= 1; ++i) {
          const long bi = b[0] + i, bj = b[1] + j, bk = b[2] + k;
          if (bi < 0 || bj < 0 || bk < 0 || bi >= nbins[0] || bj >= nbins[1] || bk >= nbins[2]) continue;
          auto it = bins.find(bi + nbins[0] * (bj + nbins[1] * bk));
          if (it == bins.end()) continue;
          for (Index f : it->second)
            if (close(e, f) && (!keep || keep(std::min(e, f), std::max(e, f)))) row.push_back(f);
        }
    std::sort(row.begin(), row.end());
  }
  CellGraph g;
  g.offsets.reserve(static_cast<std::size_t>(ncells) + 1);
  g.offsets.push_back(0);
  for (const auto& row : rows) {
    g.neighbors.insert(g.neighbors.end(), row.begin(), row.end());
    g.offsets.push_back(static_cast<Index>(g.neighbors.size()));
  }
  return g;
}

}  // namespace perimorph::bonds
