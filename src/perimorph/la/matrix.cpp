#include "perimorph/la/matrix.hpp"

#include "perimorph/la/petsc_check.hpp"

#include <petscmat.h>

#include <vector>

namespace perimorph::la {

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
  PM_PETSC(MatSetOption(m_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  PM_PETSC(MatSetOption(m_, MAT_IGNORE_ZERO_ENTRIES, PETSC_FALSE));
  // Insert explicit zeros over the whole pattern so the structure is fixed
  // even where assembled values happen to be zero.
  std::vector<PetscInt> cols;
  std::vector<PetscScalar> zeros;
  for (Index r = 0; r < nb; ++r) {
    const auto row = pattern.row(r);
    cols.clear();
    for (Index c : row)
      for (Index k = 0; k < bs; ++k) cols.push_back(c * bs + k);
    zeros.assign(cols.size(), 0.0);
    for (Index k = 0; k < bs; ++k) {
      const PetscInt grow = r * bs + k;
      PM_PETSC(MatSetValues(m_, 1, &grow, static_cast<PetscInt>(cols.size()), cols.data(), zeros.data(),
                            INSERT_VALUES));
    }
  }
  finalize();
}

Matrix::~Matrix() {
  if (m_) MatDestroy(&m_);
}

Matrix::Matrix(Matrix&& other) noexcept : m_(other.m_) {
  other.m_ = nullptr;
}

Matrix& Matrix::operator=(Matrix&& other) noexcept {
  if (this != &other) {
    if (m_) MatDestroy(&m_);
    m_ = other.m_;
    other.m_ = nullptr;
  }
  return *this;
}

void Matrix::add(std::span<const Index> rows, std::span<const Index> cols, std::span<const double> values) {
  PM_PETSC(MatSetValues(m_, static_cast<PetscInt>(rows.size()), rows.data(),
                        static_cast<PetscInt>(cols.size()), cols.data(), values.data(), ADD_VALUES));
}

void Matrix::zero_entries() {
  PM_PETSC(MatZeroEntries(m_));
}

void Matrix::finalize() {
  PM_PETSC(MatAssemblyBegin(m_, MAT_FINAL_ASSEMBLY));
  PM_PETSC(MatAssemblyEnd(m_, MAT_FINAL_ASSEMBLY));
}

Matrix Matrix::duplicate() const {
  Mat copy = nullptr;
  PM_PETSC(MatDuplicate(m_, MAT_COPY_VALUES, &copy));
  return Matrix(copy);
}

void Matrix::mult(const Vector& x, Vector& y) const {
  PM_PETSC(MatMult(m_, x.handle(), y.handle()));
}

void Matrix::eliminate_dirichlet(std::span<const Index> rows, const Vector& x, Vector& rhs, double diagonal) {
  PM_PETSC(MatZeroRowsColumns(m_, static_cast<PetscInt>(rows.size()), rows.data(), diagonal, x.handle(),
                              rhs.handle()));
}

Index Matrix::rows() const {
  PetscInt m = 0, n = 0;
  PM_PETSC(MatGetSize(m_, &m, &n));
  return m;
}

double Matrix::nonzeros() const {
  MatInfo info;
  PM_PETSC(MatGetInfo(m_, MAT_GLOBAL_SUM, &info));
  return info.nz_used;
}

Eigen::MatrixXd Matrix::to_dense() const {
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
  PM_PETSC(MatSetOption(m_, MAT_SYMMETRIC, PETSC_TRUE));
  PM_PETSC(MatSetOption(m_, MAT_SYMMETRY_ETERNAL, PETSC_TRUE));
  PM_PETSC(MatSetOption(m_, MAT_SPD, PETSC_TRUE));
}

}  // namespace perimorph::la
