// Matrix::make_vector and Matrix::copy_values_from (matrix.hpp), for one
// process and distributed alike.

#include "perimorph/la/matrix.hpp"
#include "perimorph/la/petsc_check.hpp"

#include <petscmat.h>

namespace perimorph::la {

Vector Matrix::make_vector() const {
  PetscInt bs = 1;
  PM_PETSC(MatGetBlockSize(m_, &bs));
  if (distribution_) return Vector(distribution_, static_cast<int>(bs));
  return Vector(rows(), static_cast<int>(bs));
}

void Matrix::copy_values_from(const Matrix& other) {
  release_view();
  other.release_view();
  PM_PETSC(MatCopy(other.m_, m_, SAME_NONZERO_PATTERN));
}

}  // namespace perimorph::la
