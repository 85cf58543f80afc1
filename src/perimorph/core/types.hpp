#pragma once
// Basic scalar, index and small-vector types shared by every pipeline stage.

#include <Eigen/Core>

#include <cstdint>

namespace perimorph {

/// Index of a node, element or degree of freedom. Matches PetscInt (32 bit in
/// Debian's PETSc); la/ static_asserts the match.
using Index = std::int32_t;

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

/// Voigt order for 3D: xx, yy, zz, yz, xz, xy (engineering shear strains).
using Voigt6 = Eigen::Matrix<double, 6, 6>;

/// 2D models: plane strain or plane stress (ignored in 1D and 3D).
enum class PlaneMode { strain, stress };

}  // namespace perimorph
