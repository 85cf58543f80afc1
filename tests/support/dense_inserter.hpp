#pragma once
// Test support: a dense MatrixInserter (the assembly interface without any
// backend), so assembled matrices can be inspected entry by entry and
// compared bit for bit.

#include "perimorph/assembly/inserter.hpp"
#include "perimorph/core/types.hpp"

#include <Eigen/Dense>

#include <span>

namespace perimorph::testing {

/// A[rows[i], cols[j]] += values[i * cols.size() + j] (row-major blocks);
/// negative row or column indices are skipped, as in PETSc.
class DenseInserter : public assembly::MatrixInserter {
 public:
  explicit DenseInserter(Index n) : A(Eigen::MatrixXd::Zero(n, n)) {}

  void add(std::span<const Index> rows, std::span<const Index> cols,
           std::span<const double> values) override {
    for (std::size_t i = 0; i < rows.size(); ++i) {
      if (rows[i] < 0) continue;
      for (std::size_t j = 0; j < cols.size(); ++j) {
        if (cols[j] < 0) continue;
        A(rows[i], cols[j]) += values[i * cols.size() + j];
      }
    }
    ++calls;
  }

  Eigen::MatrixXd A;
  int calls = 0;  ///< number of add() calls (one per inserted block)
};

}  // namespace perimorph::testing
