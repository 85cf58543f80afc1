#include "perimorph/la/matrix.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/la/matrix_distributed_view.hpp"
#include "perimorph/la/petsc_check.hpp"

#include <petscmat.h>

#include <fmt/format.h>

#include <algorithm>
#include <vector>

namespace perimorph::la {

namespace {

bool is_seqaij(Mat m) {
  PetscBool match = PETSC_FALSE;
  PM_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(m), MATSEQAIJ, &match));
  return match == PETSC_TRUE;
}

}  // namespace

Matrix::Matrix(PetscMatHandle m) : m_(m), direct_(is_seqaij(m)) {}

Matrix::Matrix(const assembly::SparsityPattern& pattern) {
  const Index bs = pattern.block_size;
  const Index nb = pattern.num_block_rows();
  PM_PETSC(MatCreate(PETSC_COMM_WORLD, &m_));
  PM_PETSC(MatSetSizes(m_, nb * bs, nb * bs, PETSC_DETERMINE, PETSC_DETERMINE));
  PM_PETSC(MatSetType(m_, MATAIJ));
  PM_PETSC(MatSetBlockSize(m_, bs));
  // Block-row counts; serial: every column is in the diagonal block.
  std::vector<PetscInt> dnnz(static_cast<std::size_t>(nb)), onnz(static_cast<std::size_t>(nb), 0);
  for (Index r = 0; r < nb; ++r)
    dnnz[static_cast<std::size_t>(r)] = static_cast<PetscInt>(pattern.row(r).size());
  PM_PETSC(MatXAIJSetPreallocation(m_, bs, dnnz.data(), onnz.data(), nullptr, nullptr));
  // The whole pattern is stored (explicit zeros), so the structure is fixed
  // even where assembled values happen to be zero.
  auto expanded_row = [&](Index r, std::vector<PetscInt>& cols) {
    for (Index c : pattern.row(r))
      for (Index k = 0; k < bs; ++k) cols.push_back(c * bs + k);
  };
  if (is_seqaij(m_)) {
    // One process: the column indices of every row in one call (a copy),
    // instead of MatSetValues' per-value insertion.
    std::vector<PetscInt> ja;
    ja.reserve(pattern.columns.size() * static_cast<std::size_t>(bs * bs));
    std::vector<PetscInt> cols;
    for (Index r = 0; r < nb; ++r) {
      cols.clear();
      expanded_row(r, cols);
      for (Index k = 0; k < bs; ++k) ja.insert(ja.end(), cols.begin(), cols.end());
    }
    PM_PETSC(MatSeqAIJSetColumnIndices(m_, ja.data()));
    finalize();
    PM_PETSC(MatZeroEntries(m_));
  } else {
    std::vector<PetscInt> cols;
    std::vector<PetscScalar> zeros;
    for (Index r = 0; r < nb; ++r) {
      cols.clear();
      expanded_row(r, cols);
      zeros.assign(cols.size(), 0.0);
      for (Index k = 0; k < bs; ++k) {
        const PetscInt grow = r * bs + k;
        PM_PETSC(MatSetValues(m_, 1, &grow, static_cast<PetscInt>(cols.size()), cols.data(), zeros.data(),
                              INSERT_VALUES));
      }
    }
  }
  PM_PETSC(MatSetOption(m_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  PM_PETSC(MatSetOption(m_, MAT_IGNORE_ZERO_ENTRIES, PETSC_FALSE));
  finalize();
  direct_ = is_seqaij(m_);
}

Matrix::~Matrix() {
  if (!m_) return;
  try {
    release_view();
  } catch (...) {  // a destructor must not throw; the matrix is destroyed anyway
  }
  MatDestroy(&m_);
}

Matrix::Matrix(Matrix&& other) noexcept
    : m_(other.m_),
      distribution_(std::move(other.distribution_)),
      direct_(other.direct_),
      view_(other.view_),
      view_held_(other.view_held_),
      dview_(std::move(other.dview_)) {
  other.m_ = nullptr;
  other.view_held_ = false;
}

Matrix& Matrix::operator=(Matrix&& other) noexcept {
  if (this != &other) {
    if (m_) {
      try {
        release_view();
      } catch (...) {
      }
      MatDestroy(&m_);
    }
    m_ = other.m_;
    distribution_ = std::move(other.distribution_);
    direct_ = other.direct_;
    view_ = other.view_;
    view_held_ = other.view_held_;
    dview_ = std::move(other.dview_);
    other.m_ = nullptr;
    other.view_held_ = false;
  }
  return *this;
}

void Matrix::add(std::span<const Index> rows, std::span<const Index> cols, std::span<const double> values) {
  if (distribution_) {
    if (acquire_distributed_view()) {
      add_distributed(rows, cols, values);
      return;
    }
    // Rows of other processes skipped (negative), as add_distributed does;
    // the indices distributed.
    PetscInt bs = 1;
    PM_PETSC(MatGetBlockSize(m_, &bs));
    std::vector<PetscInt> owned(rows.size()), global_cols(cols.size());
    for (std::size_t i = 0; i < rows.size(); ++i)
      owned[i] =
          rows[i] >= 0 && distribution_->owns(rows[i] / bs) ? distribution_->global_dof(rows[i], bs) : -1;
    for (std::size_t j = 0; j < cols.size(); ++j)
      global_cols[j] = cols[j] >= 0 ? distribution_->global_dof(cols[j], bs) : -1;
    PM_PETSC(MatSetValues(m_, static_cast<PetscInt>(owned.size()), owned.data(),
                          static_cast<PetscInt>(global_cols.size()), global_cols.data(), values.data(),
                          ADD_VALUES));
    return;
  }
  if (!acquire_view()) {
    PM_PETSC(MatSetValues(m_, static_cast<PetscInt>(rows.size()), rows.data(),
                          static_cast<PetscInt>(cols.size()), cols.data(), values.data(), ADD_VALUES));
    return;
  }
  // Same semantics as MatSetValues(ADD_VALUES): negative indices skipped,
  // values summed in row-major order, an entry outside the pattern an error.
  const std::size_t nc = cols.size();
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Index r = rows[i];
    if (r < 0) continue;
    PERIMORPH_ASSERT(r < view_.n, "matrix row out of range");
    const Index* first = view_.ja + view_.ia[r];
    const Index* last = view_.ja + view_.ia[r + 1];
    const Index* at = nullptr;
    const double* vrow = values.data() + i * nc;
    for (std::size_t j = 0; j < nc; ++j) {
      const Index c = cols[j];
      if (c < 0) continue;
      if (at != nullptr && at + 1 < last && at[1] == c)
        ++at;  // the next column of a run (the components of a node)
      else {
        at = std::lower_bound(first, last, c);
        if (at == last || *at != c)
          throw Error(
              fmt::format("matrix entry ({}, {}) is outside the preallocated sparsity pattern", r, c));
      }
      view_.values[at - view_.ja] += vrow[j];
    }
  }
}

void Matrix::zero_entries() {
  release_view();
  PM_PETSC(MatZeroEntries(m_));
}

void Matrix::finalize() {
  release_view();
  PM_PETSC(MatAssemblyBegin(m_, MAT_FINAL_ASSEMBLY));
  PM_PETSC(MatAssemblyEnd(m_, MAT_FINAL_ASSEMBLY));
}

Matrix Matrix::duplicate() const {
  release_view();
  Mat copy = nullptr;
  PM_PETSC(MatDuplicate(m_, MAT_COPY_VALUES, &copy));
  Matrix out(copy);
  out.distribution_ = distribution_;
  return out;
}

void Matrix::mult(const Vector& x, Vector& y) const {
  release_view();
  PM_PETSC(MatMult(m_, x.read_handle(), y.handle()));
}

void Matrix::eliminate_dirichlet(std::span<const Index> rows, const Vector& x, Vector& rhs, double diagonal) {
  release_view();
  if (distribution_) {
    // Each process names the rows it owns (distributed numbering).
    PetscInt bs = 1;
    PM_PETSC(MatGetBlockSize(m_, &bs));
    std::vector<PetscInt> owned;
    for (Index r : rows)
      if (distribution_->owns(r / bs)) owned.push_back(distribution_->global_dof(r, bs));
    PM_PETSC(MatZeroRowsColumns(m_, static_cast<PetscInt>(owned.size()), owned.data(), diagonal,
                                x.read_handle(), rhs.handle()));
    return;
  }
  PM_PETSC(MatZeroRowsColumns(m_, static_cast<PetscInt>(rows.size()), rows.data(), diagonal, x.read_handle(),
                              rhs.handle()));
}

Vector Matrix::diagonal() const {
  release_view();
  PetscInt bs = 1;
  PM_PETSC(MatGetBlockSize(m_, &bs));
  Vector d = distribution_ ? Vector(distribution_, static_cast<int>(bs)) : Vector(rows(), 1);
  PM_PETSC(MatGetDiagonal(m_, d.handle()));
  return d;
}

std::vector<double> Matrix::diagonal_at(std::span<const Index> rows) const {
  release_view();
  if (distribution_) {
    std::vector<double> out;
    const std::vector<Index> ones(rows.size(), 1);
    for (const Eigen::MatrixXd& b : distributed_blocks(rows, ones)) out.push_back(b(0, 0));
    return out;
  }
  std::vector<double> out(rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k) PM_PETSC(MatGetValues(m_, 1, &rows[k], 1, &rows[k], &out[k]));
  return out;
}

Matrix Matrix::without_zero_blocks() const {
  release_view();
  PetscInt bs = 1;
  PM_PETSC(MatGetBlockSize(m_, &bs));
  const Index n = rows();
  const Index nb = n / bs;
  // Block columns with a non-zero entry, per block row.
  assembly::SparsityPattern pattern;
  pattern.block_size = static_cast<int>(bs);
  pattern.row_offsets.assign(1, 0);
  std::vector<Index> cols;
  for (Index br = 0; br < nb; ++br) {
    cols.clear();
    for (Index k = 0; k < bs; ++k) {
      PetscInt ncols = 0;
      const PetscInt* c = nullptr;
      const PetscScalar* v = nullptr;
      PM_PETSC(MatGetRow(m_, br * bs + k, &ncols, &c, &v));
      for (PetscInt j = 0; j < ncols; ++j)
        if (v[j] != 0.0 || c[j] / bs == br) cols.push_back(c[j] / bs);
      PM_PETSC(MatRestoreRow(m_, br * bs + k, &ncols, &c, &v));
    }
    std::sort(cols.begin(), cols.end());
    cols.erase(std::unique(cols.begin(), cols.end()), cols.end());
    pattern.columns.insert(pattern.columns.end(), cols.begin(), cols.end());
    pattern.row_offsets.push_back(static_cast<Index>(pattern.columns.size()));
  }
  Matrix out(pattern);
  std::vector<Index> kept;
  std::vector<double> values;
  for (Index r = 0; r < n; ++r) {
    PetscInt ncols = 0;
    const PetscInt* c = nullptr;
    const PetscScalar* v = nullptr;
    PM_PETSC(MatGetRow(m_, r, &ncols, &c, &v));
    kept.clear();
    values.clear();
    const auto row_blocks = pattern.row(r / bs);
    for (PetscInt j = 0; j < ncols; ++j)
      if (std::binary_search(row_blocks.begin(), row_blocks.end(), c[j] / bs)) {
        kept.push_back(c[j]);
        values.push_back(v[j]);
      }
    PM_PETSC(MatRestoreRow(m_, r, &ncols, &c, &v));
    const Index row[1] = {r};
    for (std::size_t j = 0; j < kept.size(); ++j) out.add(row, {&kept[j], 1}, {&values[j], 1});
  }
  out.finalize();
  return out;
}

Eigen::MatrixXd Matrix::block(std::span<const Index> dofs) const {
  release_view();
  if (distribution_) {
    const Index size[1] = {static_cast<Index>(dofs.size())};
    return distributed_blocks(dofs, size).front();
  }
  const auto n = static_cast<PetscInt>(dofs.size());
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> out(n, n);
  if (n > 0) PM_PETSC(MatGetValues(m_, n, dofs.data(), n, dofs.data(), out.data()));
  return out;
}

std::vector<Eigen::MatrixXd> Matrix::blocks(std::span<const std::vector<Index>> sets) const {
  if (distribution_) {
    std::vector<Index> dofs, sizes;
    for (const auto& s : sets) {
      dofs.insert(dofs.end(), s.begin(), s.end());
      sizes.push_back(static_cast<Index>(s.size()));
    }
    return distributed_blocks(dofs, sizes);
  }
  std::vector<Eigen::MatrixXd> out;
  out.reserve(sets.size());
  for (const auto& s : sets) out.push_back(block(s));
  return out;
}

Index Matrix::rows() const {
  release_view();
  PetscInt m = 0, n = 0;
  PM_PETSC(MatGetSize(m_, &m, &n));
  return m;
}

double Matrix::nonzeros() const {
  release_view();
  MatInfo info;
  PM_PETSC(MatGetInfo(m_, MAT_GLOBAL_SUM, &info));
  return info.nz_used;
}

void Matrix::visit_rows(
    const std::function<void(Index, std::span<const Index>, std::span<const double>)>& visit) const {
  PERIMORPH_ASSERT(!distribution_, "visit_rows reads every row: a matrix of one process");
  visit_owned_rows(visit);  // one process owns every row
}

assembly::SparsityPattern Matrix::block_pattern() const {
  release_view();
  PetscInt bs = 1;
  PM_PETSC(MatGetBlockSize(m_, &bs));
  const Index n = rows();
  assembly::SparsityPattern pattern;
  pattern.block_size = static_cast<int>(bs);
  pattern.row_offsets.assign(1, 0);
  for (Index r = 0; r < n; r += bs) {
    PetscInt ncols = 0;
    const PetscInt* cols = nullptr;
    PM_PETSC(MatGetRow(m_, r, &ncols, &cols, nullptr));
    for (PetscInt j = 0; j < ncols; j += bs) pattern.columns.push_back(cols[j] / bs);
    PM_PETSC(MatRestoreRow(m_, r, &ncols, &cols, nullptr));
    pattern.row_offsets.push_back(static_cast<Index>(pattern.columns.size()));
  }
  return pattern;
}

void Matrix::set_values(std::span<const double> values) {
  release_view();
  if (static_cast<double>(values.size()) != nonzeros())
    throw Error(
        fmt::format("set_values: {} values for a matrix with {} stored entries", values.size(), nonzeros()));
  if (!is_seqaij(m_)) throw Error("set_values: only on one process (MATSEQAIJ)");
  PetscScalar* v = nullptr;
  PM_PETSC(MatSeqAIJGetArray(m_, &v));
  std::copy(values.begin(), values.end(), v);
  PM_PETSC(MatSeqAIJRestoreArray(m_, &v));
}

Eigen::MatrixXd Matrix::to_dense() const {
  release_view();
  if (distribution_) return distributed_to_dense();
  const Index n = rows();
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  for (PetscInt r = 0; r < n; ++r) {
    PetscInt ncols = 0;
    const PetscInt* cols = nullptr;
    const PetscScalar* vals = nullptr;
    PM_PETSC(MatGetRow(m_, r, &ncols, &cols, &vals));
    for (PetscInt k = 0; k < ncols; ++k) A(r, cols[k]) = vals[k];
    PM_PETSC(MatRestoreRow(m_, r, &ncols, &cols, &vals));
  }
  return A;
}

void Matrix::set_spd() {
  release_view();
  PM_PETSC(MatSetOption(m_, MAT_SYMMETRIC, PETSC_TRUE));
  PM_PETSC(MatSetOption(m_, MAT_SYMMETRY_ETERNAL, PETSC_TRUE));
  PM_PETSC(MatSetOption(m_, MAT_SPD, PETSC_TRUE));
}

}  // namespace perimorph::la
