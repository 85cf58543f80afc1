#pragma once
// Error checking for PETSc calls inside la/*.cpp (never included by headers).

#include "perimorph/core/error.hpp"

#include <petscsys.h>

#include <fmt/format.h>

namespace perimorph::la::detail {

inline void check(PetscErrorCode ierr, const char* call) {
  if (ierr == 0) return;
  const char* text = nullptr;
  PetscErrorMessage(ierr, &text, nullptr);
  throw SolverError(
      fmt::format("PETSc call {} failed: {} (code {})", call, text ? text : "?", static_cast<int>(ierr)));
}

}  // namespace perimorph::la::detail

#define PM_PETSC(call) ::perimorph::la::detail::check((call), #call)
