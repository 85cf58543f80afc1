#pragma once
// The small interface through which assembly writes (STYLE.md habit 3).
// Assembly never sees a backend: la/ implements these for PETSc, and the tests
// implement them with dense matrices.

#include "perimorph/core/types.hpp"

#include <span>

namespace perimorph::assembly {

/// Adds a dense block: A[rows[i], cols[j]] += values[i * cols.size() + j].
/// Negative row or column indices are skipped (PETSc's convention).
class MatrixInserter {
 public:
  virtual ~MatrixInserter() = default;
  virtual void add(std::span<const Index> rows, std::span<const Index> cols,
                   std::span<const double> values) = 0;
};

}  // namespace perimorph::assembly
