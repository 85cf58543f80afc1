#pragma once
// Linear elastic materials of the local model (THEORY §1): isotropic (E, ν)
// and orthotropic (engineering constants in material axes, rotated to the
// mesh). Stiffness tensors are 6×6 Voigt matrices (xx, yy, zz, yz, xz, xy,
// engineering shear) and are reduced to the dimension of the model:
// plane strain or plane stress in 2D (xx, yy, xy), uniaxial stress in 1D.

#include "perimorph/core/types.hpp"

#include <Eigen/Dense>

namespace perimorph::fem {

using PlaneMode = perimorph::PlaneMode;

struct IsotropicElasticity {
  double E = 0.0;
  double nu = 0.0;
};

/// Engineering constants in the material axes; νij is the contraction along j
/// under uniaxial stress along i (νij/Ei = νji/Ej). `axes` holds the material
/// axes e1, e2, e3 as columns, in mesh coordinates (a rotation).
struct OrthotropicElasticity {
  double E1 = 0.0, E2 = 0.0, E3 = 0.0;
  double nu12 = 0.0, nu13 = 0.0, nu23 = 0.0;
  double G12 = 0.0, G13 = 0.0, G23 = 0.0;
  Mat3 axes = Mat3::Identity();
};

Voigt6 stiffness_voigt(const IsotropicElasticity& m);
Voigt6 stiffness_voigt(const OrthotropicElasticity& m);

/// Rotates a stiffness given in material axes to mesh axes: C'_ijkl =
/// R_ip R_jq R_kr R_ls C_pqrs with R = axes.
Voigt6 rotate_stiffness(const Voigt6& C, const Mat3& axes);

/// Reduces a 3D stiffness to the model's dimension: 1 → [E_xx] under
/// uniaxial stress, 2 → 3×3 plane strain or plane stress, 3 → unchanged.
Eigen::MatrixXd reduce_stiffness(const Voigt6& C, int dim, PlaneMode mode);

/// Size of the Voigt vector in dimension dim: 1, 3 or 6.
constexpr int voigt_size(int dim) {
  return dim == 1 ? 1 : dim == 2 ? 3 : 6;
}

/// Checks that the material is physically admissible (positive moduli,
/// positive-definite stiffness). Returns an empty string if so, otherwise a
/// sentence saying why not.
std::string admissibility_problem(const IsotropicElasticity& m);
std::string admissibility_problem(const OrthotropicElasticity& m);

}  // namespace perimorph::fem
