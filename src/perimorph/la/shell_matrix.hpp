#pragma once
// A matrix-free operator inside PETSc (MATSHELL, RAII, move-only): y = A x by
// a callback on plain arrays, so that a Krylov solver (LinearSolver) can use
// an operator that is never assembled, preconditioned by an assembled matrix
// (LinearSolver::set_operators). Only the product is provided; PETSc
// preconditioners that need entries (GAMG, Jacobi) take them from the
// preconditioning matrix.

#include "perimorph/core/types.hpp"
#include "perimorph/la/distribution.hpp"
#include "perimorph/la/petsc_fwd.hpp"
#include "perimorph/la/vector.hpp"

#include <functional>
#include <memory>
#include <span>
#include <vector>

namespace perimorph::la {

class ShellMatrix {
 public:
  /// y ← A x, both of length `size` (y is overwritten). Called by PETSc from
  /// one thread; the callback may use OpenMP inside.
  using Apply = std::function<void(std::span<const double> x, std::span<double> y)>;

  ShellMatrix(Index size, int block_size, Apply apply);
  /// Spread over the processes by `distribution` (dof nodes of `block_size`
  /// entries): `apply` gets x whole in the assembly's numbering and must write
  /// the rows this process owns of y (whole length, assembly numbering; the
  /// rest is ignored). Before each product the entries of x at `reads` (the
  /// nodes apply reads for its rows, assembly numbering: the halo) are brought
  /// from their owners, and only those: x is 0 elsewhere. With `reads` empty,
  /// all of x is gathered on every process.
  ShellMatrix(std::shared_ptr<const Distribution> distribution, int block_size, Apply apply,
              std::vector<Index> reads = {});
  /// Entries of x this process receives from others before each product
  /// (0 on one process).
  Index received_per_product() const;
  ~ShellMatrix();
  ShellMatrix(ShellMatrix&& other) noexcept;
  ShellMatrix& operator=(ShellMatrix&& other) noexcept;
  ShellMatrix(const ShellMatrix&) = delete;
  ShellMatrix& operator=(const ShellMatrix&) = delete;

  /// y ← A x
  void mult(const Vector& x, Vector& y) const;
  Index rows() const { return size_; }
  /// The PETSc matrix (la/ only).
  PetscMatHandle handle() const { return m_; }
  /// What PETSc's product callback reads (la/ only).
  struct Context;

 private:
  /// Both constructors: `size` rows (where spread, the sum of the owned
  /// rows: PETSC_DETERMINE), `distribution` null on one process.
  ShellMatrix(std::shared_ptr<const Distribution> distribution, int block_size, Apply apply, Index size,
              std::vector<Index> reads);
  PetscMatHandle m_ = nullptr;
  Index size_ = 0;
  std::unique_ptr<Context> context_;  ///< the shell's context: a stable address
};

}  // namespace perimorph::la
