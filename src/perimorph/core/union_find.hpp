#pragma once
// Disjoint sets over 0 … n−1 (union–find with path halving), whose root is
// always the smallest member: the parts it finds come out in the order of
// their smallest members, whatever order the joins came in.

#include "perimorph/core/types.hpp"

#include <numeric>
#include <utility>
#include <vector>

namespace perimorph {

class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), Index{0}); }

  /// The smallest member of a's set.
  Index find(Index a) {
    while (parent_[static_cast<std::size_t>(a)] != a) {
      auto& p = parent_[static_cast<std::size_t>(a)];
      p = parent_[static_cast<std::size_t>(p)];
      a = p;
    }
    return a;
  }

  /// Merges the sets of a and b.
  void join(Index a, Index b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (b < a) std::swap(a, b);
    parent_[static_cast<std::size_t>(b)] = a;
  }

 private:
  std::vector<Index> parent_;
};

}  // namespace perimorph
