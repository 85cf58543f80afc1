#pragma once
// A PETSc vector (RAII, move-only). Made with a size, it is serial: the local
// layout equals the global one. Made with a la::Distribution (issue 17), each
// process stores the entries of the dof nodes it owns, in the distributed
// numbering; assign_replicated and to_replicated convert from and to the
// assembly's numbering. The element-wise operations (assign, add, add_at,
// set_at, to_std) act on the owned entries; norm2, dot and all_finite on all.

#include "perimorph/core/types.hpp"
#include "perimorph/la/distribution.hpp"
#include "perimorph/la/petsc_fwd.hpp"

#include <memory>
#include <span>
#include <vector>

namespace perimorph::la {

class OwnedDofs;

class Vector {
 public:
  Vector(Index size, int block_size);
  /// Spread over the processes by `distribution` (dof nodes of `block_size`
  /// entries), zero.
  Vector(std::shared_ptr<const Distribution> distribution, int block_size);
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
  /// this[indices[k]] += values[k] (repeated indices add up). Indices in the
  /// assembly's numbering; distributed, each process changes the entries it
  /// owns and skips the others (call it with the same arguments on every process).
  void add_at(std::span<const Index> indices, std::span<const double> values);
  /// this[indices[k]] = value (as add_at).
  void set_at(std::span<const Index> indices, double value);
  /// this[indices[k]] = values[k] (as add_at; indices unique).
  void set_at(std::span<const Index> indices, std::span<const double> values);
  std::vector<double> to_std() const;
  /// Sets the owned entries from `values`, the whole vector in the assembly's
  /// numbering (the same on every process). Without a distribution: assign.
  void assign_replicated(std::span<const double> values);
  /// The whole vector in the assembly's numbering on every process
  /// (collective). Without a distribution: to_std.
  std::vector<double> to_replicated() const;
  /// The entries at `owned`'s dofs (this process's, la::OwnedDofs), in its
  /// order (nothing is sent). Without a distribution: to_std.
  std::vector<double> at_owned(const OwnedDofs& owned) const;
  /// Sets the entries at `owned`'s dofs from `values`, in its order. Without
  /// a distribution: assign.
  void assign_owned(const OwnedDofs& owned, std::span<const double> values);
  /// The distribution (null for a serial vector).
  const Distribution* distribution() const { return distribution_.get(); }
  /// The same, shared (for what outlives the vector: la::NodeGather).
  const std::shared_ptr<const Distribution>& shared_distribution() const { return distribution_; }
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
  std::shared_ptr<const Distribution> distribution_;
  /// Where entry i (assembly numbering) is in this process's array; −1 if
  /// another process owns it. bs: the block size.
  Index local_index(Index i, Index bs) const;
  /// add_at (add) or set_at (values) on the owned entries.
  void change_at(std::span<const Index> indices, std::span<const double> values, bool add);
};

}  // namespace perimorph::la
