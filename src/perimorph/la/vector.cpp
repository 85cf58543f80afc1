#include "perimorph/la/vector.hpp"

#include "perimorph/la/owned_dofs.hpp"
#include "perimorph/la/petsc_check.hpp"
#include "perimorph/la/petsc_session.hpp"

#include <petscvec.h>

#include <algorithm>
#include <cmath>

namespace perimorph::la {

Vector::Vector(Index size, int block_size) {
  PM_PETSC(VecCreate(PETSC_COMM_WORLD, &v_));
  PM_PETSC(VecSetSizes(v_, size, PETSC_DECIDE));
  PM_PETSC(VecSetBlockSize(v_, block_size));
  PM_PETSC(VecSetType(v_, VECSTANDARD));
  PM_PETSC(VecSet(v_, 0.0));
}

Vector::Vector(std::shared_ptr<const Distribution> distribution, int block_size)
    : distribution_(std::move(distribution)) {
  PM_PETSC(VecCreate(PETSC_COMM_WORLD, &v_));
  PM_PETSC(VecSetSizes(v_, distribution_->owned_nodes() * block_size, PETSC_DETERMINE));
  PM_PETSC(VecSetBlockSize(v_, block_size));
  PM_PETSC(VecSetType(v_, VECSTANDARD));
  PM_PETSC(VecSet(v_, 0.0));
}

Vector::~Vector() {
  if (v_) VecDestroy(&v_);
}

Vector::Vector(Vector&& other) noexcept : v_(other.v_), distribution_(std::move(other.distribution_)) {
  other.v_ = nullptr;
}

Vector& Vector::operator=(Vector&& other) noexcept {
  if (this != &other) {
    if (v_) VecDestroy(&v_);
    v_ = other.v_;
    distribution_ = std::move(other.distribution_);
    other.v_ = nullptr;
  }
  return *this;
}

Index Vector::size() const {
  PetscInt n = 0;
  PM_PETSC(VecGetLocalSize(v_, &n));
  return n;
}

void Vector::set_all(double value) {
  PM_PETSC(VecSet(v_, value));
}

void Vector::assign(std::span<const double> values) {
  PERIMORPH_ASSERT(static_cast<Index>(values.size()) == size(), "vector size mismatch");
  PetscScalar* a = nullptr;
  PM_PETSC(VecGetArray(v_, &a));
  std::copy(values.begin(), values.end(), a);
  PM_PETSC(VecRestoreArray(v_, &a));
}

void Vector::add(std::span<const double> values) {
  PERIMORPH_ASSERT(static_cast<Index>(values.size()) == size(), "vector size mismatch");
  PetscScalar* a = nullptr;
  PM_PETSC(VecGetArray(v_, &a));
  for (std::size_t i = 0; i < values.size(); ++i) a[i] += values[i];
  PM_PETSC(VecRestoreArray(v_, &a));
}

Index Vector::local_index(Index i, Index bs) const {
  if (!distribution_) return i;
  const Distribution& d = *distribution_;
  const Index node = d.to_distributed[static_cast<std::size_t>(i / bs)];
  return node >= d.begin && node < d.end ? (node - d.begin) * bs + i % bs : -1;
}

void Vector::add_at(std::span<const Index> indices, std::span<const double> values) {
  change_at(indices, values, true);
}

void Vector::set_at(std::span<const Index> indices, double value) {
  PetscInt bs = 1;
  PM_PETSC(VecGetBlockSize(v_, &bs));
  PetscScalar* a = nullptr;
  PM_PETSC(VecGetArray(v_, &a));
  for (Index i : indices) {
    const Index at = local_index(i, bs);
    if (at >= 0) a[at] = value;
  }
  PM_PETSC(VecRestoreArray(v_, &a));
}

void Vector::set_at(std::span<const Index> indices, std::span<const double> values) {
  change_at(indices, values, false);
}

void Vector::change_at(std::span<const Index> indices, std::span<const double> values, bool add) {
  PERIMORPH_ASSERT(indices.size() == values.size(), "add_at/set_at: sizes differ");
  PetscInt bs = 1;
  PM_PETSC(VecGetBlockSize(v_, &bs));
  PetscScalar* a = nullptr;
  PM_PETSC(VecGetArray(v_, &a));
  for (std::size_t k = 0; k < indices.size(); ++k) {
    const Index at = local_index(indices[k], bs);
    if (at < 0) continue;
    if (add)
      a[at] += values[k];
    else
      a[at] = values[k];
  }
  PM_PETSC(VecRestoreArray(v_, &a));
}

std::vector<double> Vector::to_std() const {
  const PetscScalar* a = nullptr;
  PM_PETSC(VecGetArrayRead(v_, &a));
  std::vector<double> out(a, a + size());
  PM_PETSC(VecRestoreArrayRead(v_, &a));
  return out;
}

void Vector::assign_replicated(std::span<const double> values) {
  if (!distribution_) {
    assign(values);
    return;
  }
  const Distribution& d = *distribution_;
  PetscInt bs = 1;
  PM_PETSC(VecGetBlockSize(v_, &bs));
  PERIMORPH_ASSERT(static_cast<Index>(values.size()) == d.num_nodes() * bs, "vector size mismatch");
  PetscScalar* a = nullptr;
  PM_PETSC(VecGetArray(v_, &a));
  for (Index n = 0; n < d.num_nodes(); ++n) {
    if (!d.owns(n)) continue;
    const Index at = (d.to_distributed[static_cast<std::size_t>(n)] - d.begin) * bs;
    for (Index k = 0; k < bs; ++k) a[at + k] = values[static_cast<std::size_t>(n * bs + k)];
  }
  PM_PETSC(VecRestoreArray(v_, &a));
}

std::vector<double> Vector::to_replicated() const {
  if (!distribution_) return to_std();
  const Distribution& d = *distribution_;
  PetscInt bs = 1;
  PM_PETSC(VecGetBlockSize(v_, &bs));
  VecScatter to_all = nullptr;
  Vec all = nullptr;
  PM_PETSC(VecScatterCreateToAll(v_, &to_all, &all));
  PM_PETSC(VecScatterBegin(to_all, v_, all, INSERT_VALUES, SCATTER_FORWARD));
  PM_PETSC(VecScatterEnd(to_all, v_, all, INSERT_VALUES, SCATTER_FORWARD));
  const PetscScalar* a = nullptr;
  PM_PETSC(VecGetArrayRead(all, &a));
  std::vector<double> out(static_cast<std::size_t>(d.num_nodes() * bs));
  for (Index n = 0; n < d.num_nodes(); ++n)
    for (Index k = 0; k < bs; ++k)
      out[static_cast<std::size_t>(n * bs + k)] = a[d.to_distributed[static_cast<std::size_t>(n)] * bs + k];
  PM_PETSC(VecRestoreArrayRead(all, &a));
  PM_PETSC(VecScatterDestroy(&to_all));
  PM_PETSC(VecDestroy(&all));
  return out;
}

std::vector<double> Vector::at_owned(const OwnedDofs& owned) const {
  if (!distribution_) return to_std();
  PetscInt bs = 1;
  PM_PETSC(VecGetBlockSize(v_, &bs));
  std::vector<double> out(owned.size());
  const PetscScalar* a = nullptr;
  PM_PETSC(VecGetArrayRead(v_, &a));
  for (std::size_t j = 0; j < out.size(); ++j) out[j] = a[local_index(owned.dof(j), bs)];
  PM_PETSC(VecRestoreArrayRead(v_, &a));
  return out;
}

void Vector::assign_owned(const OwnedDofs& owned, std::span<const double> values) {
  if (!distribution_) return assign(values);
  PetscInt bs = 1;
  PM_PETSC(VecGetBlockSize(v_, &bs));
  PERIMORPH_ASSERT(
      values.size() == owned.size() && static_cast<Index>(owned.size()) == distribution_->owned_nodes() * bs,
      "assign_owned: not this process's owned entries");
  PetscScalar* a = nullptr;
  PM_PETSC(VecGetArray(v_, &a));
  for (std::size_t j = 0; j < values.size(); ++j) a[local_index(owned.dof(j), bs)] = values[j];
  PM_PETSC(VecRestoreArray(v_, &a));
}

double Vector::norm2() const {
  PetscReal n = 0;
  PM_PETSC(VecNorm(v_, NORM_2, &n));
  return n;
}

double Vector::dot(const Vector& other) const {
  PetscScalar d = 0;
  PM_PETSC(VecDot(v_, other.v_, &d));
  return d;
}

void Vector::axpy(double a, const Vector& x) {
  PM_PETSC(VecAXPY(v_, a, x.v_));
}

void Vector::copy_from(const Vector& other) {
  PM_PETSC(VecCopy(other.v_, v_));
}

bool Vector::all_finite() const {
  const PetscScalar* a = nullptr;
  PM_PETSC(VecGetArrayRead(v_, &a));
  int ok = std::all_of(a, a + size(), [](double x) { return std::isfinite(x); }) ? 1 : 0;
  PM_PETSC(VecRestoreArrayRead(v_, &a));
  if (distribution_) MPI_Allreduce(MPI_IN_PLACE, &ok, 1, MPI_INT, MPI_MIN, PETSC_COMM_WORLD);
  return ok == 1;
}

}  // namespace perimorph::la
