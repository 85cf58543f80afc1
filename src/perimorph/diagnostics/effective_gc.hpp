#pragma once
// The critical energy release rate of a given crack plane (THEORY §5, §3.3.2):
// the energy of every bond that crosses the plane when each is stretched to
// s_crit, per unit area of the plane, for the actual discretized geometry.
//
//   G = Σ_{bonds g–h crossing the plane} ½ ᾱ c_bond (s_crit |ξ|)² W_gh / A
//
// with W_gh = w_g w_h, c_bond the bond's micromodulus as the non-local
// stiffness uses it (cut-off or partial volume, angular factor included),
// ᾱ = (α_g + α_h)/2, bonds crossing a pre-crack cut left out. Three figures:
//  - the bulk closed form κ s_crit² (κ = Calibration::gc_factor; NaN for an
//    anisotropic kernel, whose G_c depends on the plane);
//  - the actual geometry: every crossing bond, over the area of the plane
//    inside the box; incomplete horizons near free faces make it lower;
//  - the bulk window: only bonds crossing farther than δ from every face of the
//    box, over the area of that part of the plane; it tends to the closed form
//    as h → 0 (quadrature error only).
//
// Units. Energies are in the case's units (stiffness × length³). In 3D the
// weights are volumes and c the calibrated micromodulus: G is energy / area.
// In 2D the weights carry the thickness t (w = t w_area) and build_discretization
// divides the kernel scale by t (model.cpp), so Σ W c = t Σ w_area w_area ĉ:
// the sum is t × (energy per unit thickness) and is divided by the plane's
// length × t. In 1D likewise with the cross-section A (the plane's area is A).
// So G is always energy per unit crack area (stiffness × length, e.g. MPa·mm).
//
// Ties. A non-local point whose signed distance to the plane is within
// 1e-12 × the box's extent is *on* the plane. A bond with both ends strictly
// on opposite sides crosses (weight 1); a bond with exactly one end on the
// plane counts with weight ½ (the mean of the two one-sided limits, moving the
// plane by ±ε); a bond with both ends on it does not cross. The window uses the
// same rule per axis for crossing points on its border.

#include "perimorph/core/types.hpp"

#include <cstddef>
#include <string>

namespace perimorph::setup {
struct Discretization;
}

namespace perimorph::diagnostics {

/// The plane through `point` with normal `normal`. 2D: a line in the xy plane
/// (normal without z component); 1D: the point x = point.x (normal ±e_x).
struct CrackPlane {
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitX();
};

/// Measure of the section of the box [lo, hi] (first `dim` axes) by the plane:
/// an area in 3D, a length in 2D, 1 or 0 in 1D (the point strictly inside or
/// not); 0 if the box is empty on some axis. `plane.normal` must be a unit
/// vector (and lie in the xy plane in 2D).
double section_measure(int dim, const Vec3& lo, const Vec3& hi, const CrackPlane& plane);

/// A sum of bond energies over (a part of) the plane.
struct PlaneSum {
  double energy = 0.0;    ///< Σ ½ ᾱ c_bond (s_crit |ξ|)² W (weights ½ for ties)
  double area = 0.0;      ///< area of that part (2D: length × thickness; 1D: cross-section)
  std::size_t bonds = 0;  ///< bonds counted (weight > 0)
  double gc() const;      ///< energy / area; NaN when the area is 0
};

struct EffectiveGc {
  CrackPlane plane;  ///< normal made unit
  double s_crit = 1.0;
  double gc_factor = 0.0;         ///< κ; NaN for an anisotropic kernel
  double closed_form = 0.0;       ///< κ s_crit²
  double horizon = 0.0;           ///< δ, the window's margin
  PlaneSum actual;                ///< every crossing bond, over the plane inside the box
  PlaneSum window;                ///< crossing points farther than δ from every face
  std::size_t touching = 0;       ///< counted bonds with one end on the plane (weight ½)
  std::size_t cut = 0;            ///< crossing bonds left out because they cross a pre-crack cut
  std::size_t reduced_alpha = 0;  ///< counted bonds with ᾱ < 1 (their energy is scaled by ᾱ)
};

/// The three figures for the plane (see the file comment). Throws InputError
/// for a case without [nonlocal], a zero normal, a normal out of the model's
/// plane (2D) or off e_x (1D), and a plane that leaves the whole box on one side.
EffectiveGc effective_gc(const setup::Discretization& model, const CrackPlane& plane, double s_crit);

}  // namespace perimorph::diagnostics
