#pragma once
// Anisotropic micromodulus c(ξ) = c_r(|ξ|) · Y(ξ/|ξ|) (THEORY §2.1, thesis
// §2.5): the angular part Y, the maps from a central-force stiffness tensor to
// its coefficients, and the Cauchy relations that a central-force tensor obeys.
//
// 3D (material axes e1, e2, e3; x = cos θ = e·e3, and with m = the components
// of e in material axes, (1 − x²) cos 2φ = m1² − m2², (1 − x²)² cos 4φ =
// (m1² − m2²)² − 4 m1² m2²):
//   orthotropic (2.73)
//     Y = a00 + a20 P2⁰ + a22 cos2φ P2² + a40 P4⁰ + a42 cos2φ P4² + a44 cos4φ P4⁴
//   transversely isotropic about e3 (2.82): a22 = a42 = a44 = 0.
// With R4 = ∫₀^δ c_r r⁴ dr, the bulk tensor (2.64) C_ijkl = R4/2 ∫_S² Y e_i e_j
// e_k e_l dΩ and its inverse map are those of THEORY §2.1.
//
// 2D (in the plane, mesh axes, θ the angle of e from x; derived in
// docs/verification/anisotropy.md): Y = a0 + a2 cos2θ + b2 sin2θ + a4 cos4θ +
// b4 sin4θ. With R3 = ∫₀^δ c_r r³ dr and K = π R3 / 2,
//   C1111 = K (3a0/4 + a2/2 + a4/8)     C2222 = K (3a0/4 − a2/2 + a4/8)
//   C1122 = C1212 = K (a0/4 − a4/8)     C1112 = K (b2/4 + b4/8)   C2212 = K (b2/4 − b4/8)
// and inversely
//   a0 = (C1111 + C2222 + 2 C1122) / (2K)   a2 = (C1111 − C2222) / K
//   a4 = (C1111 + C2222 − 6 C1122) / K      b2 = 2 (C1112 + C2212) / K
//   b4 = 4 (C1112 − C2212) / K.
// In material axes of an orthotropic material b2 = b4 = 0, leaving the
// a0 + a2 cos2θ + a4 cos4θ of the issue; keeping b2, b4 takes any in-plane
// rotation (and any 2D central-force tensor, 5 constants) without angles.

#include "perimorph/core/types.hpp"

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace perimorph::peridynamics {

enum class AngularKind { isotropic, orthotropic, transversely_isotropic, planar };

const char* to_string(AngularKind k);

/// The angular factor Y of the micromodulus; Y ≡ 1 for `isotropic`.
struct AngularPart {
  AngularKind kind = AngularKind::isotropic;
  /// orthotropic: a00 a20 a22 a40 a42 a44; transversely isotropic: a0 a2 a4 at
  /// the places of a00 a20 a40 (others 0); planar: a0 a2 b2 a4 b4.
  std::array<double, 6> a{};
  /// Material axes e1, e2, e3 as columns, in mesh coordinates (3D kinds).
  Mat3 axes = Mat3::Identity();

  /// Y in the direction of ξ, |ξ| = r > 0. Centrosymmetric: Y(−e) = Y(e).
  double operator()(const Vec3& xi, double r) const {
    if (kind == AngularKind::isotropic) return 1.0;
    return evaluate(xi / r);
  }
  double evaluate(const Vec3& e) const;
};

/// Orthotropic coefficients from the normal components C1111, C2222, C3333,
/// C1122, C1133, C2233 of `C` (Voigt, material axes; the shear entries are
/// not read: central forces fix them), for a radial part with moment R4.
AngularPart orthotropic_angular(const Voigt6& C, double R4, const Mat3& axes);

/// Transversely isotropic coefficients (eqs. 2.84–2.86 with δ⁵ → 5 R4) from
/// C1111, C1133, C3333 of `C` (material axes; needs C2222 = C1111, C2233 =
/// C1133 and C1122 = C1111/3, which callers check).
AngularPart transversely_isotropic_angular(const Voigt6& C, double R4, const Mat3& axes);

/// Planar (2D) coefficients from a 2D central-force tensor C2 (Voigt xx, yy,
/// xy, mesh axes) for a radial part with moment R3.
AngularPart planar_angular(const Eigen::Matrix3d& C2, double R3);

/// The bulk tensor R_m/2 ∫ Y e⊗e⊗e⊗e (Voigt, dimension dim = 2 or 3), with
/// the radial moment R_m given (R3 in 2D, R4 in 3D), by a product rule exact
/// for Y of degree ≤ 4: the map back from coefficients to C (round trips).
Eigen::MatrixXd angular_bulk_tensor(const AngularPart& Y, int dim, double radial_moment);

/// Smallest and largest Y over directions (sampled on a fine grid): a
/// negative minimum means bonds in those directions push instead of pull.
std::array<double, 2> angular_range(const AngularPart& Y, int dim);

/// One Cauchy relation that a tensor breaks: the two Voigt entries that
/// central forces make equal, their names and values.
struct CauchyViolation {
  std::string relation;  ///< e.g. "C1212 = C1122"
  std::string shear;     ///< the shear-type entry, e.g. "C1212"
  std::string normal;    ///< its partner, e.g. "C1122"
  double shear_value = 0.0;
  double normal_value = 0.0;
};

/// The Cauchy relations (full index symmetry C_ijkl = C_ikjl) that C (Voigt,
/// dim 2: xx yy xy; dim 3: xx yy zz yz xz xy) breaks by more than
/// rtol · max|C|. 2D has one (C1212 = C1122), 3D six.
std::vector<CauchyViolation> cauchy_violations(const Eigen::MatrixXd& C, int dim, double rtol = 1e-6);

/// The nearest central-force tensor to C in the Frobenius norm of the
/// fourth-order tensor: its totally symmetric part, e.g. C1122' = C1212' =
/// (C1122 + 2 C1212)/3; other entries unchanged.
Eigen::MatrixXd nearest_central_force(const Eigen::MatrixXd& C, int dim);

}  // namespace perimorph::peridynamics
