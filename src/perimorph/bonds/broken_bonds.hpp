#pragma once
// The bonds that have failed (THEORY §5): irreversible, so the store only
// grows. A bond joins non-local point g of cell e and point h of cell f; it
// is kept under its cell pair with e ≤ f as the code g · n + h (n points per
// cell), sorted, so the pair kernel can skip it by a binary search. For e = f
// both orders (g, h) and (h, g) are stored, as the kernel visits both.
// Nothing else is stored per bond: intact bonds stay implicit.

#include "perimorph/core/types.hpp"

#include <cassert>
#include <cstdint>
#include <map>
#include <span>
#include <vector>

namespace perimorph::bonds {

/// One bond: point g of cell e, point h of cell f.
struct BondId {
  Index e = 0, f = 0;
  int g = 0, h = 0;
  /// The same bond with e ≤ f (and g < h when e = f).
  BondId canonical() const;
};

class BrokenBonds {
 public:
  BrokenBonds() = default;
  BrokenBonds(Index num_cells, int points_per_cell);

  /// Marks the bond broken; false if it already was.
  bool add(const BondId& bond);
  bool contains(const BondId& bond) const;
  /// Sorted codes g · n + h of the broken bonds of the pair (e, f), e ≤ f.
  std::span<const std::uint32_t> pair(Index e, Index f) const;
  /// Any broken bond with a point in cell c.
  bool touches(Index c) const {
    assert(per_cell_.empty() || (c >= 0 && static_cast<std::size_t>(c) < per_cell_.size()));
    return !per_cell_.empty() && per_cell_[static_cast<std::size_t>(c)] > 0;
  }
  std::size_t size() const { return count_; }
  bool empty() const { return count_ == 0; }
  int points_per_cell() const { return n_; }
  /// The bond's cells and points exist in this set's model.
  bool valid(const BondId& b) const {
    const auto cells = static_cast<Index>(by_cell_.size());
    return b.e >= 0 && b.e < cells && b.f >= 0 && b.f < cells && b.g >= 0 && b.g < n_ && b.h >= 0 && b.h < n_;
  }

 private:
  int n_ = 0;
  std::size_t count_ = 0;
  std::vector<std::map<Index, std::vector<std::uint32_t>>> by_cell_;  ///< [e][f], e ≤ f
  std::vector<int> per_cell_;                                         ///< broken bonds touching each cell
};

}  // namespace perimorph::bonds
