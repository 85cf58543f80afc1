#pragma once
// Radial micromodulus kernels of the non-local model (THEORY §1.1) and their
// calibration against the local isotropic material (THEORY §2). All kernels
// are cut off at |ξ| = δ.

#include "perimorph/core/types.hpp"
#include "perimorph/peridynamics/anisotropy.hpp"

#include <string>

namespace perimorph::peridynamics {

enum class KernelShape { constant, conical, exponential, gaussian, pmb };

const char* to_string(KernelShape s);

/// c(r) = scale · φ(r) for r < δ, 0 otherwise, with φ = 1, 1 − r/δ,
/// r² exp(−r/l), r² exp(−r²/l²), 1/r for constant, conical, exponential,
/// gaussian, pmb. c is the force per unit *elongation* of a bond (the thesis'
/// convention, THEORY §1.1). `pmb` is the prototype micro-elastic brittle
/// model (Silling & Askari 2005; Peridigm's "Elastic", LAMMPS' peri/pmb): a
/// constant force per unit *stretch* c_pmb, i.e. c_pmb / r per elongation, so
/// its scale is their c_pmb (3D: 18K/(πδ⁴)).
/// a bond ξ acts with c(|ξ|) · Y(ξ/|ξ|), Y the angular part (THEORY §2.1;
/// Y ≡ 1 for an isotropic kernel).
struct Micromodulus {
  KernelShape shape = KernelShape::constant;
  double horizon = 1.0;  ///< δ
  double length = 1.0;   ///< l (exponential and gaussian only)
  double scale = 1.0;    ///< ĉ
  AngularPart angular;   ///< Y (anisotropy.hpp)

  /// φ(r) (without the scale); 0 for r ≥ δ.
  double shape_value(double r) const;
  double operator()(double r) const { return scale * shape_value(r); }
  /// c(ξ) = c(r) Y(ξ/r) for a bond ξ of length r > 0.
  double bond(const Vec3& xi, double r) const { return (*this)(r)*angular(xi, r); }
  /// ∫₀^δ φ(r) r^k dr (without the scale), exact to round-off.
  double shape_moment(int k) const;
  double moment(int k) const { return scale * shape_moment(k); }
};

/// What calibration gives (THEORY §2 table and §5): the scale ĉ, the Lamé
/// constant λ = μ of the equivalent local material, its E and ν, and the
/// factor κ with G_c = κ · s_crit².
struct Calibration {
  double scale = 0.0;
  double lame = 0.0;  ///< λ = μ (in 1D: not defined, 0)
  double E = 0.0;
  double nu = 0.0;
  double gc_factor = 0.0;
};

/// Poisson ratio that a central-force (bond-based) material has: 1/4 in 3D and
/// plane strain, 1/3 in plane stress; 1D has none (returns NaN).
double cauchy_poisson_ratio(int dim, PlaneMode mode);

/// Empty if ν is representable by a bond-based material in this setting,
/// otherwise a sentence saying why not.
std::string cauchy_problem(int dim, PlaneMode mode, double nu);

/// Scale ĉ such that the non-local material equals the local isotropic one
/// with Young's modulus E (THEORY §2), with κ for G_c = κ s_crit² (THEORY §5).
/// `kernel.scale` is ignored.
Calibration calibrate_isotropic(const Micromodulus& kernel, int dim, PlaneMode mode, double E);

/// The angular part that makes c_r · Y, c_r = kernel.shape_value (scale 1),
/// equal to the central-force stiffness C (THEORY §2.1): in 3D C is the 6×6
/// Voigt tensor in material axes `axes` and `kind` is orthotropic or
/// transversely_isotropic; in 2D C is the 3×3 tensor (xx, yy, xy) in mesh axes
/// and the result is planar. The caller has checked the Cauchy relations.
AngularPart calibrate_angular(const Micromodulus& kernel, int dim, const Eigen::MatrixXd& C, const Mat3& axes,
                              AngularKind kind);

}  // namespace perimorph::peridynamics
