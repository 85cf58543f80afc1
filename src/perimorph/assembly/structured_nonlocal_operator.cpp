#include "perimorph/assembly/structured_nonlocal_operator.hpp"

#include "perimorph/bonds/nonlocal_points.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/dofs/dof_map.hpp"
#include "perimorph/mesh/mesh.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace perimorph::assembly {

namespace {

/// Collects the entries of the rows of one cell's dofs.
class RowCapture final : public MatrixInserter {
 public:
  RowCapture(Index first, int count) : first_(first), count_(count) {}
  void add(std::span<const Index> rows, std::span<const Index> cols,
           std::span<const double> values) override {
    for (std::size_t i = 0; i < rows.size(); ++i) {
      if (rows[i] < first_ || rows[i] >= first_ + count_) continue;
      for (std::size_t j = 0; j < cols.size(); ++j)
        if (cols[j] >= 0) entries[{rows[i], cols[j]}] += values[i * cols.size() + j];
    }
  }
  std::map<std::pair<Index, Index>, double> entries;

 private:
  Index first_;
  int count_;
};

}  // namespace

OffsetBlocks offset_blocks(const NonlocalSpace& space, Index centre) {
  const auto& mesh = space.mesh;
  const int dim = mesh.dim();
  if (!mesh.structure || space.points.per_cell != 1 || space.dofmap.cell_nodes(centre).size() != 1)
    throw Error(
        "the matrix-free non-local operator needs a structured box mesh with one non-local point "
        "per cell (discretization = \"discontinuous-constant\")");
  const auto& layout = *mesh.structure;
  const Index node = space.dofmap.cell_nodes(centre)[0];
  RowCapture capture(node * dim, dim);
  NonlocalOptions options;
  options.include_pair = [centre](Index e, Index f) { return e == centre || f == centre; };
  assemble_nonlocal(space, capture, options);
  // Column node → offset from the centre.
  std::map<Index, Index> cell_of_node;
  for (Index c = 0; c < mesh.num_cells(); ++c) cell_of_node[space.dofmap.cell_nodes(c)[0]] = c;
  const auto ijk0 = layout.cell_ijk(centre);
  const int r = static_cast<int>(std::ceil(space.kernel.horizon / layout.spacing.minCoeff()));
  for (int d = 0; d < dim; ++d)
    if (ijk0[static_cast<std::size_t>(d)] < r ||
        ijk0[static_cast<std::size_t>(d)] + r >= layout.cells[static_cast<std::size_t>(d)])
      throw Error(
          fmt::format("offset_blocks: cell {} is closer than the horizon to a face of the grid", centre));
  std::map<std::array<int, 3>, std::vector<double>> by_offset;
  for (const auto& [rc, v] : capture.entries) {
    const Index col_node = rc.second / dim;
    if (col_node == node) continue;
    const auto ijk = layout.cell_ijk(cell_of_node.at(col_node));
    std::array<int, 3> o{};
    for (int d = 0; d < 3; ++d)
      o[static_cast<std::size_t>(d)] =
          static_cast<int>(ijk[static_cast<std::size_t>(d)] - ijk0[static_cast<std::size_t>(d)]);
    auto& b = by_offset[o];
    b.resize(static_cast<std::size_t>(dim * dim), 0.0);
    b[static_cast<std::size_t>((rc.first - node * dim) * dim + rc.second % dim)] = -v;
  }
  OffsetBlocks out;
  out.dim = dim;
  for (const auto& [o, b] : by_offset) {
    out.offsets.push_back(o);
    out.blocks.insert(out.blocks.end(), b.begin(), b.end());
  }
  return out;
}

StructuredNonlocalOperator::StructuredNonlocalOperator(OffsetBlocks blocks, std::array<Index, 3> cells,
                                                       std::vector<Index> node_of_cell)
    : StructuredNonlocalOperator(std::move(blocks), cells, GridWindow{{0, 0, 0}, cells},
                                 std::move(node_of_cell)) {}

StructuredNonlocalOperator::StructuredNonlocalOperator(OffsetBlocks blocks, std::array<Index, 3> cells,
                                                       GridWindow window, std::vector<Index> node_of_cell)
    : b_(std::move(blocks)), n_(cells), w_(window), node_(std::move(node_of_cell)) {
  PERIMORPH_ASSERT(static_cast<Index>(node_.size()) == w_.count(), "a node (or -1) for every window cell");
  for (int d = 0; d < 3; ++d)
    PERIMORPH_ASSERT(w_.lo[static_cast<std::size_t>(d)] >= 0 &&
                         w_.lo[static_cast<std::size_t>(d)] + w_.size[static_cast<std::size_t>(d)] <=
                             n_[static_cast<std::size_t>(d)],
                     "the window lies in the grid");
  for (Index n : node_) nodes_ = std::max(nodes_, n + 1);
}

template <class Visit>
void StructuredNonlocalOperator::for_each_neighbour(Index c, Visit&& visit) const {
  const Index w0 = w_.size[0], w1 = w_.size[1];
  const Index i = c % w0, j = (c / w0) % w1, k = c / (w0 * w1);
  for (std::size_t q = 0; q < b_.offsets.size(); ++q) {
    const Index a = i + b_.offsets[q][0], b = j + b_.offsets[q][1], e = k + b_.offsets[q][2];
    const Index ga = w_.lo[0] + a, gb = w_.lo[1] + b, ge = w_.lo[2] + e;  // in the grid
    if (ga < 0 || ga >= n_[0] || gb < 0 || gb >= n_[1] || ge < 0 || ge >= n_[2]) continue;
    visit(q, a, b, e);
  }
}

void StructuredNonlocalOperator::apply(std::span<const double> x, std::span<double> y,
                                       std::span<const char> cells) const {
  const int dim = b_.dim;
  const Index w0 = w_.size[0], w1 = w_.size[1];
  const Index total = w_.count();
  const std::size_t m = b_.offsets.size();
  if (m == 0) {
    std::fill(y.begin(), y.end(), 0.0);
    return;
  }
  const int* off = b_.offsets.front().data();
  const double* B = b_.blocks.data();
  // The grid's bounds in window coordinates (the window's own on the whole grid).
  const Index a0 = -w_.lo[0], a1 = n_[0] - w_.lo[0], b0 = -w_.lo[1], b1 = n_[1] - w_.lo[1], e0 = -w_.lo[2],
              e1 = n_[2] - w_.lo[2];
  // The hot loop of the matrix-free solve, written out (for_each_neighbour's
  // lambda cost 15 % on P4).
#pragma omp parallel for schedule(static)
  for (Index c = 0; c < total; ++c) {
    if (!cells.empty() && cells[static_cast<std::size_t>(c)] == 0) continue;
    const Index node = node_[static_cast<std::size_t>(c)];
    if (node < 0) continue;  // not in the piece
    const Index i = c % w0, j = (c / w0) % w1, k = c / (w0 * w1);
    const std::size_t row = static_cast<std::size_t>(node) * static_cast<std::size_t>(dim);
    double acc[3] = {0.0, 0.0, 0.0};
    double xi[3] = {0.0, 0.0, 0.0};
    for (int d = 0; d < dim; ++d) xi[d] = x[row + static_cast<std::size_t>(d)];
    for (std::size_t q = 0; q < m; ++q) {
      const Index a = i + off[3 * q], b = j + off[3 * q + 1], e = k + off[3 * q + 2];
      if (a < a0 || a >= a1 || b < b0 || b >= b1 || e < e0 || e >= e1) continue;
      const std::size_t col =
          static_cast<std::size_t>(node_[static_cast<std::size_t>(a + w0 * (b + w1 * e))]) *
          static_cast<std::size_t>(dim);
      const double* Bq = B + q * static_cast<std::size_t>(dim * dim);
      double diff[3] = {0.0, 0.0, 0.0};
      for (int d = 0; d < dim; ++d) diff[d] = xi[d] - x[col + static_cast<std::size_t>(d)];
      for (int r = 0; r < dim; ++r)
        for (int s = 0; s < dim; ++s) acc[r] += Bq[r * dim + s] * diff[s];
    }
    for (int d = 0; d < dim; ++d) y[row + static_cast<std::size_t>(d)] = acc[d];
  }
}

std::vector<Index> StructuredNonlocalOperator::nodes_read(std::span<const char> cells) const {
  const Index w0 = w_.size[0], w1 = w_.size[1], w2 = w_.size[2];
  const Index total = w_.count();
  std::vector<char> read(static_cast<std::size_t>(total), 0);
  for (Index c = 0; c < total; ++c) {
    if (cells[static_cast<std::size_t>(c)] == 0) continue;
    read[static_cast<std::size_t>(c)] = 1;
    for_each_neighbour(c, [&](std::size_t, Index a, Index b, Index e) {
      const Index f = a + w0 * (b + w1 * e);
      if (a < 0 || a >= w0 || b < 0 || b >= w1 || e < 0 || e >= w2 || node_[static_cast<std::size_t>(f)] < 0)
        throw Error(
            fmt::format("the matrix-free operator: a bond of cell ({}, {}, {}) of the grid reaches a "
                        "cell its piece does not hold",
                        w_.lo[0] + c % w0, w_.lo[1] + (c / w0) % w1, w_.lo[2] + c / (w0 * w1)));
      read[static_cast<std::size_t>(f)] = 1;
    });
  }
  std::vector<Index> nodes;
  for (Index c = 0; c < total; ++c)
    if (read[static_cast<std::size_t>(c)]) nodes.push_back(node_[static_cast<std::size_t>(c)]);
  std::sort(nodes.begin(), nodes.end());
  return nodes;
}

SparsityPattern StructuredNonlocalOperator::sparsity(std::span<const char> cells) const {
  const Index w0 = w_.size[0], w1 = w_.size[1];
  const Index total = w_.count();
  std::vector<std::vector<Index>> rows(static_cast<std::size_t>(nodes_));
  for (Index c = 0; c < total; ++c) {
    if (!cells.empty() && !cells[static_cast<std::size_t>(c)]) continue;
    const Index node = node_[static_cast<std::size_t>(c)];
    if (node < 0) continue;
    auto& r = rows[static_cast<std::size_t>(node)];
    r.push_back(node);
    for_each_neighbour(c, [&](std::size_t, Index a, Index b, Index e) {
      r.push_back(node_[static_cast<std::size_t>(a + w0 * (b + w1 * e))]);
    });
  }
  SparsityPattern p;
  p.block_size = b_.dim;
  p.row_offsets.assign(1, 0);
  for (auto& r : rows) {
    std::sort(r.begin(), r.end());
    r.erase(std::unique(r.begin(), r.end()), r.end());
    p.columns.insert(p.columns.end(), r.begin(), r.end());
    p.row_offsets.push_back(static_cast<Index>(p.columns.size()));
  }
  return p;
}

void StructuredNonlocalOperator::assemble(MatrixInserter& K, std::span<const char> cells) const {
  const int dim = b_.dim;
  const auto dd = static_cast<std::size_t>(dim * dim);
  const Index w0 = w_.size[0], w1 = w_.size[1];
  const Index total = w_.count();
  std::vector<Index> rows(static_cast<std::size_t>(dim)), cols(static_cast<std::size_t>(dim));
  std::vector<double> diag(dd), off(dd);
  for (Index c = 0; c < total; ++c) {
    if (!cells.empty() && !cells[static_cast<std::size_t>(c)]) continue;
    const Index node = node_[static_cast<std::size_t>(c)];
    if (node < 0) continue;
    for (int d = 0; d < dim; ++d) rows[static_cast<std::size_t>(d)] = node * dim + d;
    std::fill(diag.begin(), diag.end(), 0.0);
    for_each_neighbour(c, [&](std::size_t q, Index a, Index b, Index e) {
      const double* B = b_.blocks.data() + q * dd;
      for (std::size_t t = 0; t < dd; ++t) {
        diag[t] += B[t];
        off[t] = -B[t];
      }
      const Index f = node_[static_cast<std::size_t>(a + w0 * (b + w1 * e))];
      for (int d = 0; d < dim; ++d) cols[static_cast<std::size_t>(d)] = f * dim + d;
      K.add(rows, cols, off);
    });
    K.add(rows, rows, diag);
  }
}

}  // namespace perimorph::assembly
