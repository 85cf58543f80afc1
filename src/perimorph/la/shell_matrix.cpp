#include "perimorph/la/shell_matrix.hpp"

#include "perimorph/la/petsc_check.hpp"

#include <petscmat.h>

#include <utility>

namespace perimorph::la {

namespace {

PetscErrorCode shell_mult(Mat A, Vec x, Vec y) {
  void* ctx = nullptr;
  PetscCall(MatShellGetContext(A, &ctx));
  const auto& apply = *static_cast<const ShellMatrix::Apply*>(ctx);
  PetscInt n = 0;
  PetscCall(VecGetLocalSize(x, &n));
  const PetscScalar* xa = nullptr;
  PetscScalar* ya = nullptr;
  PetscCall(VecGetArrayRead(x, &xa));
  PetscCall(VecGetArrayWrite(y, &ya));
  apply(std::span<const double>(xa, static_cast<std::size_t>(n)),
        std::span<double>(ya, static_cast<std::size_t>(n)));
  PetscCall(VecRestoreArrayWrite(y, &ya));
  PetscCall(VecRestoreArrayRead(x, &xa));
  return 0;
}

}  // namespace

ShellMatrix::ShellMatrix(Index size, int block_size, Apply apply)
    : size_(size), apply_(std::make_unique<Apply>(std::move(apply))) {
  PM_PETSC(MatCreateShell(PETSC_COMM_WORLD, size, size, size, size, apply_.get(), &m_));
  PM_PETSC(MatSetBlockSize(m_, block_size));
  PM_PETSC(MatShellSetOperation(m_, MATOP_MULT, reinterpret_cast<void (*)(void)>(&shell_mult)));
  PM_PETSC(MatSetOption(m_, MAT_SYMMETRIC, PETSC_TRUE));
}

ShellMatrix::~ShellMatrix() {
  if (m_) MatDestroy(&m_);
}

ShellMatrix::ShellMatrix(ShellMatrix&& other) noexcept
    : m_(std::exchange(other.m_, nullptr)), size_(other.size_), apply_(std::move(other.apply_)) {}

ShellMatrix& ShellMatrix::operator=(ShellMatrix&& other) noexcept {
  if (this != &other) {
    if (m_) MatDestroy(&m_);
    m_ = std::exchange(other.m_, nullptr);
    size_ = other.size_;
    apply_ = std::move(other.apply_);
  }
  return *this;
}

void ShellMatrix::mult(const Vector& x, Vector& y) const {
  PM_PETSC(MatMult(m_, x.read_handle(), y.handle()));
}

}  // namespace perimorph::la
