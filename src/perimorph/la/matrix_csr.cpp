// The CSR arrays la::Matrix's add() writes into directly (matrix.hpp): borrowed
// from PETSc and given back before any other operation.

#include "perimorph/la/matrix.hpp"
#include "perimorph/la/petsc_check.hpp"

#include <petscmat.h>

namespace perimorph::la {

bool Matrix::borrow_csr(PetscMatHandle a, CsrView& view) {
  PetscInt n = 0;
  const PetscInt *ia = nullptr, *ja = nullptr;
  PetscBool done = PETSC_FALSE;
  PM_PETSC(MatGetRowIJ(a, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done));
  if (!done) return false;
  PetscScalar* v = nullptr;
  PM_PETSC(MatSeqAIJGetArray(a, &v));
  view = {ia, ja, v, n};
  return true;
}

void Matrix::return_csr(PetscMatHandle a, const CsrView& view) {
  PetscScalar* v = view.values;
  PM_PETSC(MatSeqAIJRestoreArray(a, &v));
  PetscInt n = view.n;
  const PetscInt *ia = view.ia, *ja = view.ja;
  PetscBool done = PETSC_FALSE;
  PM_PETSC(MatRestoreRowIJ(a, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done));
}

bool Matrix::acquire_view() {
  if (view_held_) return true;
  if (!direct_ || !borrow_csr(m_, view_)) return false;
  view_held_ = true;
  return true;
}

void Matrix::release_view() const {
  release_distributed_view();
  if (!view_held_) return;
  return_csr(m_, view_);
  view_ = {};
  view_held_ = false;
}

}  // namespace perimorph::la
