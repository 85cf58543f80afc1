#pragma once
// Opaque PETSc handle types, so that la/ headers can be included anywhere
// without exposing PETSc: only la/*.cpp include the PETSc headers.

struct _p_Mat;
struct _p_Vec;
struct _p_KSP;
struct _p_SNES;

namespace perimorph::la {
using PetscMatHandle = _p_Mat*;
using PetscVecHandle = _p_Vec*;
using PetscKspHandle = _p_KSP*;
using PetscSnesHandle = _p_SNES*;
}  // namespace perimorph::la
