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
    : n_(points_per_cell), touched_(static_cast<std::size_t>(num_cells), false) {}

bool BrokenBonds::add(const BondId& bond) {
  const BondId b = bond.canonical();
  PERIMORPH_ASSERT(b.e >= 0 && static_cast<std::size_t>(b.f) < touched_.size(), "bond cell out of range");
  PERIMORPH_ASSERT(b.g >= 0 && b.g < n_ && b.h >= 0 && b.h < n_ && !(b.e == b.f && b.g == b.h),
                   "bond point out of range");
  auto& codes = by_pair_[key(b.e, b.f)];
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
  touched_[static_cast<std::size_t>(b.e)] = true;
  touched_[static_cast<std::size_t>(b.f)] = true;
  return true;
}

bool BrokenBonds::contains(const BondId& bond) const {
  const BondId b = bond.canonical();
  const auto codes = pair(b.e, b.f);
  return std::binary_search(codes.begin(), codes.end(),
                            static_cast<std::uint32_t>(b.g * n_) + static_cast<std::uint32_t>(b.h));
}

std::span<const std::uint32_t> BrokenBonds::pair(Index e, Index f) const {
  assert(touched_.empty() || (e >= 0 && e <= f && static_cast<std::size_t>(f) < touched_.size()));
  // Most pairs have no failed bond: the two bits decide without hashing.
  if (!touches(e) || !touches(f)) return {};
  const auto it = by_pair_.find(key(e, f));
  if (it == by_pair_.end()) return {};
  return it->second;
}

std::size_t BrokenBonds::bytes() const {
  // libstdc++'s node: the next pointer, the key and the vector; a pointer per bucket.
  std::size_t b = touched_.size() / 8 + by_pair_.bucket_count() * sizeof(void*);
  for (const auto& [k, codes] : by_pair_)
    b += sizeof(void*) + sizeof(k) + sizeof(codes) + codes.capacity() * sizeof(std::uint32_t);
  return b;
}

}  // namespace perimorph::bonds
