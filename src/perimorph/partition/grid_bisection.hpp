#pragma once
// coordinate_bisection of a box grid's cells (mesh::make_box, no hole or
// cut), computed from the grid alone (issue 17, item 1: a set-up with no
// array per cell of the whole mesh). The same part for every cell as
// coordinate_bisection of the whole mesh gives.
//
// Why it can be: the centroids of a slab of cells along an axis share their
// coordinate along it (make_box: a node's coordinate along an axis depends on
// its index along it alone), and the slabs' coordinates increase. So
// coordinate_bisection's order along axis a (coordinate, then cell number) is
// the order of the keys (slab along a, cell number), and each set of its
// recursion is the grid's cells under a few cuts "key along a below
// (s, c)". Within a row of the grid along x such a set is one interval of
// cells: a set is counted, and the cut through it found, row by row (a binary
// search), with no list of its cells. A cut is computed when a cell's part or
// a part's bounds first need it, then kept.

#include "perimorph/core/types.hpp"
#include "perimorph/mesh/mesh.hpp"

#include <array>
#include <map>
#include <utility>
#include <vector>

namespace perimorph::partition {

class GridBisection {
 public:
  /// The bisection of the cells of `layout` (its box_cells empty: the whole
  /// grid) in `dim` dimensions into `parts`. Throws InputError if parts < 1
  /// or parts > cells (coordinate_bisection's message), Error if two slabs'
  /// centroids do not increase along an axis (no such box in double).
  GridBisection(const mesh::StructuredLayout& layout, int dim, int parts);

  int parts() const { return parts_; }
  /// The part of box cell b (make_box's number: x fastest).
  int owner(Index b) const;
  /// The grid index range [lo, hi) along each axis of the cells of `part`:
  /// the smallest box holding them.
  std::pair<std::array<Index, 3>, std::array<Index, 3>> bounds(int part) const;

 private:
  /// Cells whose key along `axis`, (slab, cell number), is below (slab, cell)
  /// when `below`, else at or above it.
  struct Constraint {
    int axis = 0;
    Index slab = 0, cell = 0;
    bool below = true;
  };
  /// A set's cell count and the smallest and largest slab of its cells along
  /// each axis.
  struct Extent {
    Index count = 0;
    std::array<Index, 3> lo{}, hi{};
  };
  struct Cut {
    int axis = 0;
    Index slab = 0, cell = 0;
  };

  Extent extent(const std::vector<Constraint>& set) const;
  Index count(const std::vector<Constraint>& set) const { return extent(set).count; }
  /// The cut of the set of parts [first, first + q): its first ⌊q/2⌋ parts
  /// get the cells below it (coordinate_bisection's bisect).
  const Cut& cut(const std::vector<Constraint>& set, int first, int q) const;
  /// The recursion from the whole grid down to a part, to the lower side of
  /// each cut (first, q) where `lower` says: the part reached, `set` its cells.
  /// (Lower: bool(const Cut&, int first, int q); defined and used in the .cpp alone.)
  template <class Lower>
  int descend(Lower lower, std::vector<Constraint>& set) const;
  /// The set of `part`'s cells.
  std::vector<Constraint> set_of(int part) const;
  /// The coordinate along `axis` of the centroids of slab s (Mesh::cell_centroid's sum).
  double centroid(int axis, Index s) const;

  mesh::StructuredLayout layout_;
  int dim_ = 1, parts_ = 1;
  std::array<Index, 3> n_{1, 1, 1};
  mutable std::map<std::pair<int, int>, Cut> cuts_;  ///< by (first, q)
};

}  // namespace perimorph::partition
