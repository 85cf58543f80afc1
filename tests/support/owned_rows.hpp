#pragma once
// A distributed matrix's owned rows in the distributed numbering, to compare
// matrices assembled on different numberings row by row, bit for bit.

#include "perimorph/la/matrix.hpp"

#include <span>
#include <tuple>
#include <vector>

namespace perimorph::testing {

using Rows = std::vector<std::tuple<Index, std::vector<Index>, std::vector<double>>>;

inline Rows owned_rows(const la::Matrix& K) {
  Rows out;
  K.visit_owned_rows([&](Index r, std::span<const Index> cols, std::span<const double> vals) {
    out.emplace_back(r, std::vector<Index>(cols.begin(), cols.end()),
                     std::vector<double>(vals.begin(), vals.end()));
  });
  return out;
}

}  // namespace perimorph::testing
