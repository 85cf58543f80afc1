#pragma once
// Which pairs of non-local points are bonds, and the micromodulus each acts
// with (THEORY §4): one filter for every loop over bonds (the pair kernel, the
// stretch pass, the morphed C, the effective G_c), so that they all count the
// same bonds. A pair x_g–x_h (ξ = x_h − x_g) is a bond when
//   0 < |ξ|² < reach²         (bond_reach_squared: the open horizon, or δ plus
//                              the partial-volume boxes),
//   c_bond(ξ) ≠ 0             (bond_micromodulus: partial-volume weight and
//                              angular factor included),
//   no pre-crack cut crosses it (Cut::crosses, closed cut).
// The α weight (ᾱ for the stiffness, α_g − α_h for the morphed C) and failed
// bonds (keyed by cell pair) are the callers'.

#include "perimorph/core/cut.hpp"
#include "perimorph/core/types.hpp"
#include "perimorph/peridynamics/horizon_edge.hpp"
#include "perimorph/peridynamics/micromodulus.hpp"

#include <cmath>
#include <span>

namespace perimorph::peridynamics {

/// Bonds are kept for |ξ|² < horizon_cutoff_squared(δ). The horizon is open
/// (|ξ| < δ) and a bond within a relative 1e-10 of δ counts as exactly δ and
/// is left out: on grids with δ/h rational, many point pairs lie exactly δ
/// apart, and round-off in their coordinates must not decide bond by bond.
inline double horizon_cutoff_squared(double delta) {
  return delta * delta * (1.0 - 1e-10);
}

/// The micromodulus a bond ξ (|ξ|² = r2 > 0) acts with, 0 if there is no
/// bond: c(|ξ|) inside the open horizon with the plain cut-off (half_g null),
/// φ c(r_eff) (r_eff/|ξ|)² with the partial-volume rule (horizon_edge.hpp),
/// times the angular factor Y(ξ/|ξ|) (anisotropy.hpp) either way.
/// Either way the bond's stiffness is W ᾱ c_bond e eᵀ.
template <int D>
double bond_micromodulus(const Micromodulus& c, const Vec3& xi, double r2, const Vec3* half_g,
                         const Vec3* half_h) {
  const double r = std::sqrt(r2);
  if (half_g == nullptr) return r2 < horizon_cutoff_squared(c.horizon) ? c.bond(xi, r) : 0.0;
  const EdgeWeight w = edge_weight<D>(xi, r, *half_g, *half_h, c.horizon);
  if (w.fraction == 0.0) return 0.0;
  const double Y = c.angular(xi, r);
  if (w.fraction == 1.0 && w.r_eff == r) return c(r) * Y;
  return w.fraction * c(w.r_eff) * (w.r_eff * w.r_eff) / r2 * Y;
}

/// True if the bond x_g–x_h crosses one of the cuts (a pre-crack removes it).
inline bool bond_cut(const Vec3& a, const Vec3& b, std::span<const Cut> cuts) {
  for (const auto& cut : cuts)
    if (cut.crosses(a, b)) return true;
  return false;
}

/// |ξ|² must be below this for a pair to be a bond: horizon_cutoff_squared(δ)
/// with the plain cut-off; (δ + half_g + half_h)² with the partial-volume rule,
/// `half_sum` bounding the two boxes' half-widths (bond_micromodulus decides).
inline double bond_reach_squared(double horizon, bool partial, double half_sum) {
  const double outer = horizon + half_sum;
  return partial ? outer * outer : horizon_cutoff_squared(horizon);
}

/// c_bond of the pair x_g–x_h (ξ = x_h − x_g, |ξ|² = r2, 0 < r2 < reach²),
/// 0 if a cut crosses it or it is no bond: the same value as
/// pair_bond(...).c_bond, with the cut tested first. The crossing test is
/// cheaper than the micromodulus (an exp for the exponential and gaussian
/// kernels), and near a pre-crack many pairs cross it: the loops that need
/// only c_bond (pair kernel, stretch pass, morphed C) use this order.
template <int D>
double uncut_bond_micromodulus(const Micromodulus& c, const Vec3& xg, const Vec3& xh, const Vec3& xi,
                               double r2, const Vec3* half_g, const Vec3* half_h, std::span<const Cut> cuts) {
  if (!cuts.empty() && bond_cut(xg, xh, cuts)) return 0.0;
  return bond_micromodulus<D>(c, xi, r2, half_g, half_h);
}

/// The filter's verdict on one pair: c_bond > 0 for a bond, else 0; `cut` is
/// set when the pair would be a bond but a cut crosses it.
struct PairBond {
  double c_bond = 0.0;
  bool cut = false;
};

/// The filter for the pair x_g–x_h with ξ = x_h − x_g, |ξ|² = r2 (the caller
/// has them, having tested 0 < r2 < reach²): c_bond, then the cuts. half_g,
/// half_h: the points' box half-widths (partial volume) or null (cut-off).
template <int D>
PairBond pair_bond(const Micromodulus& c, const Vec3& xg, const Vec3& xh, const Vec3& xi, double r2,
                   const Vec3* half_g, const Vec3* half_h, std::span<const Cut> cuts) {
  const double cb = bond_micromodulus<D>(c, xi, r2, half_g, half_h);
  if (cb == 0.0) return {};
  if (!cuts.empty() && bond_cut(xg, xh, cuts)) return {0.0, true};
  return {cb, false};
}

/// True if 0 < r2 < reach2: the pair may be a bond (pair_bond decides).
inline bool within_reach(double r2, double reach2) {
  return r2 < reach2 && r2 != 0.0;
}

}  // namespace perimorph::peridynamics
