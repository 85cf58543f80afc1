#pragma once
// The bonds that have failed (THEORY §5): irreversible, so the store only
// grows. A bond joins non-local point g of cell e and point h of cell f; it
// is kept under its cell pair with e ≤ f as the code g · n + h (n points per
// cell), sorted, so the pair kernel can skip it by a binary search. For e = f
// both orders (g, h) and (h, g) are stored, as the kernel visits both.
// Nothing else is stored per bond: intact bonds stay implicit. The store is
// as large as the failures, not the model: a hash of the cell pairs that
// have a failed bond and a bit per cell (every process holds the whole set,
// so a byte per cell would be paid P times over; issue 17).

#include "perimorph/core/types.hpp"

#include <cassert>
#include <cstdint>
#include <span>
#include <unordered_map>
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
    assert(touched_.empty() || (c >= 0 && static_cast<std::size_t>(c) < touched_.size()));
    return !touched_.empty() && touched_[static_cast<std::size_t>(c)];
  }
  std::size_t size() const { return count_; }
  bool empty() const { return count_ == 0; }
  int points_per_cell() const { return n_; }
  /// The bond's cells and points exist in this set's model.
  bool valid(const BondId& b) const {
    const auto cells = static_cast<Index>(touched_.size());
    return b.e >= 0 && b.e < cells && b.f >= 0 && b.f < cells && b.g >= 0 && b.g < n_ && b.h >= 0 && b.h < n_;
  }

  /// Bytes held: the pairs' codes, their hash and the bit per cell.
  std::size_t bytes() const;

 private:
  static std::uint64_t key(Index e, Index f) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(e)) << 32U) | static_cast<std::uint32_t>(f);
  }
  int n_ = 0;
  std::size_t count_ = 0;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> by_pair_;  ///< key(e, f), e ≤ f
  std::vector<bool> touched_;  ///< a broken bond has a point in the cell
};

}  // namespace perimorph::bonds
