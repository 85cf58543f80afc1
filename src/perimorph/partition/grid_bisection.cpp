#include "perimorph/partition/grid_bisection.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/mesh/box.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace perimorph::partition {

GridBisection::GridBisection(const mesh::StructuredLayout& layout, int dim, int parts)
    : layout_(layout), dim_(dim), parts_(parts) {
  PERIMORPH_ASSERT(layout.box_cells.empty(), "a grid bisection is of a whole grid");
  PERIMORPH_ASSERT(dim >= 1 && dim <= 3, "grid dimension");
  for (int d = 0; d < dim; ++d) n_[static_cast<std::size_t>(d)] = layout.cells[static_cast<std::size_t>(d)];
  const Index cells = n_[0] * n_[1] * n_[2];
  if (parts < 1 || parts > cells)
    throw InputError(
        fmt::format("cannot partition {} cells into {} parts: give 1 to {} parts", cells, parts, cells));
  for (int d = 0; d < dim; ++d)
    for (Index s = 0; s + 1 < n_[static_cast<std::size_t>(d)]; ++s)
      if (!(centroid(d, s) < centroid(d, s + 1)))
        throw Error(
            fmt::format("grid bisection: the centroids of slabs {} and {} along axis {} do not "
                        "increase; the grid's order is not the centroids' order",
                        s, s + 1, d));
}

double GridBisection::centroid(int axis, Index s) const {
  // Mesh::cell_centroid: the sum of the cell's nodes in make_box's order, over
  // their count (a power of two: the division is exact either way).
  const int npc = 1 << dim_;
  double sum = 0.0;
  for (int a = 0; a < npc; ++a) {
    std::array<Index, 3> ijk{0, 0, 0};
    ijk[static_cast<std::size_t>(axis)] = s + ((a >> axis) & 1);
    sum += mesh::box_node(layout_, dim_, ijk)[axis];
  }
  return sum / static_cast<double>(npc);
}

GridBisection::Extent GridBisection::extent(const std::vector<Constraint>& set) const {
  Extent out;
  out.lo = n_;
  out.hi = {-1, -1, -1};
  for (Index k = 0; k < n_[2]; ++k)
    for (Index j = 0; j < n_[1]; ++j) {
      const Index base = n_[0] * (j + n_[1] * k);  // the cell (0, j, k)
      const std::array<Index, 3> row{0, j, k};
      Index lo = 0, hi = n_[0];
      for (const Constraint& c : set) {
        // The cells of the row below the constraint's key are [0, e).
        Index e = 0;
        if (c.axis == 0) {
          e = std::min(c.slab + (base + c.slab < c.cell ? 1 : 0), n_[0]);
        } else {
          const Index t = row[static_cast<std::size_t>(c.axis)];
          e = t < c.slab ? n_[0] : t > c.slab ? 0 : std::clamp(c.cell - base, Index{0}, n_[0]);
        }
        if (c.below)
          hi = std::min(hi, e);
        else
          lo = std::max(lo, e);
      }
      if (lo >= hi) continue;
      out.count += hi - lo;
      out.lo = {std::min(out.lo[0], lo), std::min(out.lo[1], j), std::min(out.lo[2], k)};
      out.hi = {std::max(out.hi[0], hi - 1), std::max(out.hi[1], j), std::max(out.hi[2], k)};
    }
  return out;
}

const GridBisection::Cut& GridBisection::cut(const std::vector<Constraint>& set, int first, int q) const {
  if (const auto it = cuts_.find({first, q}); it != cuts_.end()) return it->second;
  const Extent e = extent(set);
  // The axis of the longest extent of the set's centroids (the first of equals).
  int axis = 0;
  if (e.count > 0) {
    auto length = [&](int d) {
      return centroid(d, e.hi[static_cast<std::size_t>(d)]) - centroid(d, e.lo[static_cast<std::size_t>(d)]);
    };
    for (int d = 1; d < dim_; ++d)
      if (length(d) > length(axis)) axis = d;
  }
  const long long n = e.count, q1 = q / 2;
  const auto n1 = static_cast<Index>((n * q1 + q / 2) / q);
  std::vector<Constraint> probe = set;
  probe.push_back({axis, 0, 0, true});
  auto below = [&](Index slab, Index cell) {
    probe.back().slab = slab;
    probe.back().cell = cell;
    return count(probe);
  };
  // The slab of the n1-th key (counting from 0), then the cell number that
  // leaves n1 keys below it.
  Index lo = 0, hi = n_[static_cast<std::size_t>(axis)] - 1;
  while (lo < hi) {
    const Index mid = lo + (hi - lo) / 2;
    if (below(mid + 1, 0) > n1)
      hi = mid;
    else
      lo = mid + 1;
  }
  const Index slab = lo;
  Index clo = 0, chi = n_[0] * n_[1] * n_[2];
  while (clo < chi) {
    const Index mid = clo + (chi - clo) / 2;
    if (below(slab, mid) >= n1)
      chi = mid;
    else
      clo = mid + 1;
  }
  return cuts_.emplace(std::pair{first, q}, Cut{axis, slab, clo}).first->second;
}

template <class Lower>
int GridBisection::descend(Lower lower, std::vector<Constraint>& set) const {
  set.clear();
  int first = 0, q = parts_;
  while (q > 1) {
    const Cut c = cut(set, first, q);
    const bool below = lower(c, first, q);
    set.push_back({c.axis, c.slab, c.cell, below});
    if (below) {
      q /= 2;
    } else {
      first += q / 2;
      q -= q / 2;
    }
  }
  return first;
}

int GridBisection::owner(Index b) const {
  PERIMORPH_ASSERT(b >= 0 && b < n_[0] * n_[1] * n_[2], "a cell of the grid");
  const std::array<Index, 3> ijk{b % n_[0], (b / n_[0]) % n_[1], b / (n_[0] * n_[1])};
  std::vector<Constraint> set;
  return descend(
      [&](const Cut& c, int, int) {
        const Index s = ijk[static_cast<std::size_t>(c.axis)];
        return s < c.slab || (s == c.slab && b < c.cell);
      },
      set);
}

std::vector<GridBisection::Constraint> GridBisection::set_of(int part) const {
  PERIMORPH_ASSERT(part >= 0 && part < parts_, "a part of the bisection");
  std::vector<Constraint> set;
  descend([&](const Cut&, int first, int q) { return part < first + q / 2; }, set);
  return set;
}

std::pair<std::array<Index, 3>, std::array<Index, 3>> GridBisection::bounds(int part) const {
  const Extent e = extent(set_of(part));
  PERIMORPH_ASSERT(e.count > 0, "a part without cells");
  return {e.lo, {e.hi[0] + 1, e.hi[1] + 1, e.hi[2] + 1}};
}

}  // namespace perimorph::partition
