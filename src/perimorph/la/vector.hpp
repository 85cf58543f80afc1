#pragma once
// A PETSc vector (RAII, move-only). Serial for now: the local layout equals
// the global one; all access goes through owned ranges so MPI can follow.

#include "perimorph/core/types.hpp"
#include "perimorph/la/petsc_fwd.hpp"

#include <span>
#include <vector>

namespace perimorph::la {

class Vector {
 public:
  Vector(Index size, int block_size);
  ~Vector();
  Vector(Vector&& other) noexcept;
  Vector& operator=(Vector&& other) noexcept;
  Vector(const Vector&) = delete;
  Vector& operator=(const Vector&) = delete;

  Index size() const;
  void set_all(double value);
  /// Replaces the owned values with `values` (size() entries).
  void assign(std::span<const double> values);
  /// Adds `values` entry-wise (size() entries).
  void add(std::span<const double> values);
  /// this[indices[k]] += values[k] (local indices; repeated indices add up).
  void add_at(std::span<const Index> indices, std::span<const double> values);
  /// this[indices[k]] = value.
  void set_at(std::span<const Index> indices, double value);
  std::vector<double> to_std() const;
  double norm2() const;
  double dot(const Vector& other) const;
  /// this ← this + a·x
  void axpy(double a, const Vector& x);
  void copy_from(const Vector& other);
  bool all_finite() const;

  /// The PETSc vector, for PETSc calls that may change it (la/ only).
  PetscVecHandle handle() { return v_; }
  /// The PETSc vector for read-only PETSc calls (PETSc takes Vec, not a
  /// const type, even where it only reads): nothing may change it through
  /// this handle.
  PetscVecHandle read_handle() const { return v_; }

 private:
  PetscVecHandle v_ = nullptr;
};

}  // namespace perimorph::la
