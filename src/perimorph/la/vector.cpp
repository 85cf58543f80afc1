#include "perimorph/la/vector.hpp"

#include "perimorph/la/petsc_check.hpp"

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

Vector::~Vector() {
  if (v_) VecDestroy(&v_);
}

Vector::Vector(Vector&& other) noexcept : v_(other.v_) {
  other.v_ = nullptr;
}

Vector& Vector::operator=(Vector&& other) noexcept {
  if (this != &other) {
    if (v_) VecDestroy(&v_);
    v_ = other.v_;
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

void Vector::add_at(std::span<const Index> indices, std::span<const double> values) {
  PERIMORPH_ASSERT(indices.size() == values.size(), "add_at: sizes differ");
  PetscScalar* a = nullptr;
  PM_PETSC(VecGetArray(v_, &a));
  for (std::size_t k = 0; k < indices.size(); ++k) a[indices[k]] += values[k];
  PM_PETSC(VecRestoreArray(v_, &a));
}

void Vector::set_at(std::span<const Index> indices, double value) {
  PetscScalar* a = nullptr;
  PM_PETSC(VecGetArray(v_, &a));
  for (Index i : indices) a[i] = value;
  PM_PETSC(VecRestoreArray(v_, &a));
}

std::vector<double> Vector::to_std() const {
  const PetscScalar* a = nullptr;
  PM_PETSC(VecGetArrayRead(v_, &a));
  std::vector<double> out(a, a + size());
  PM_PETSC(VecRestoreArrayRead(v_, &a));
  return out;
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
  const bool ok = std::all_of(a, a + size(), [](double x) { return std::isfinite(x); });
  PM_PETSC(VecRestoreArrayRead(v_, &a));
  return ok;
}

}  // namespace perimorph::la
