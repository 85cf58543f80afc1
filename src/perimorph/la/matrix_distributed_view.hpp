#pragma once
// la/ internal: what a distributed la::Matrix holds while add() writes into
// PETSc's arrays (matrix_distributed.cpp).

#include "perimorph/la/matrix.hpp"

#include <petscmat.h>

namespace perimorph::la {

struct Matrix::DistributedView {
  /// MPIAIJ's blocks: owned columns, the others (borrowed); on one process
  /// (SeqAIJ) the matrix itself and no off block (null).
  Mat diag = nullptr, off = nullptr;
  const PetscInt* garray = nullptr;  ///< the off block's columns, global and ascending
  CsrView d, o;                      ///< their arrays, borrowed until release
  PetscInt rstart = 0, rend = 0;     ///< owned rows (= owned columns)
  PetscInt bs = 1;                   ///< the block size (components a dof node)
};

}  // namespace perimorph::la
