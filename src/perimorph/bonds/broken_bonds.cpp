#include "perimorph/bonds/broken_bonds.hpp"

#include "perimorph/core/error.hpp"

#include <algorithm>
#include <cassert>
#include <utility>

namespace perimorph::bonds {

BondId BondId::canonical() const {
  if (e < f || (e == f && g < h)) return *this;
  return {f, e, h, g};
}

BrokenBonds::BrokenBonds(Index num_cells, int points_per_cell)
    : n_(points_per_cell),
      by_cell_(static_cast<std::size_t>(num_cells)),
      per_cell_(static_cast<std::size_t>(num_cells), 0) {}

bool BrokenBonds::add(const BondId& bond) {
  const BondId b = bond.canonical();
  PERIMORPH_ASSERT(b.e >= 0 && static_cast<std::size_t>(b.f) < by_cell_.size(), "bond cell out of range");
  PERIMORPH_ASSERT(b.g >= 0 && b.g < n_ && b.h >= 0 && b.h < n_ && !(b.e == b.f && b.g == b.h),
                   "bond point out of range");
  auto& codes = by_cell_[static_cast<std::size_t>(b.e)][b.f];
  auto insert = [&](std::uint32_t code) {
    const auto at = std::lower_bound(codes.begin(), codes.end(), code);
    if (at != codes.end() && *at == code) return false;
    codes.insert(at, code);
    return true;
  };
  const auto n = static_cast<std::uint32_t>(n_);
  if (!insert(static_cast<std::uint32_t>(b.g) * n + static_cast<std::uint32_t>(b.h))) return false;
  if (b.e == b.f) insert(static_cast<std::uint32_t>(b.h) * n + static_cast<std::uint32_t>(b.g));
  ++count_;
  ++per_cell_[static_cast<std::size_t>(b.e)];
  if (b.f != b.e) ++per_cell_[static_cast<std::size_t>(b.f)];
  return true;
}

bool BrokenBonds::contains(const BondId& bond) const {
  const BondId b = bond.canonical();
  const auto codes = pair(b.e, b.f);
  return std::binary_search(codes.begin(), codes.end(),
                            static_cast<std::uint32_t>(b.g * n_) + static_cast<std::uint32_t>(b.h));
}

std::span<const std::uint32_t> BrokenBonds::pair(Index e, Index f) const {
  if (by_cell_.empty()) return {};
  assert(e >= 0 && e <= f && static_cast<std::size_t>(f) < by_cell_.size());
  const auto& row = by_cell_[static_cast<std::size_t>(e)];
  const auto it = row.find(f);
  if (it == row.end()) return {};
  return it->second;
}

}  // namespace perimorph::bonds
