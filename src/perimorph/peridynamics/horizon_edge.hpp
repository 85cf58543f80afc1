#pragma once
// Partial-volume treatment of the horizon edge (an option of the bond
// quadrature, THEORY §4).
//
// With plain Gauss points a bond (g, h) counts fully when |ξ| < δ and not at
// all otherwise: the hard cut-off of the kernel is integrated to first order in
// the point spacing, and kernels whose integrand is large at r = δ (the
// exponential kernel with l = δ/5 weighs c r⁴ most at r = δ) carry an error of
// a few per cent that only falls like h. The partial-volume rule gives each
// point a box (its share of the cell: half-widths b_i = ½ Σ_d |J_id| w_d, the
// 1D Gauss weights w_d) and weighs a bond near the edge by the fraction of the
// box pair (x_g + B_g, x_h + B_h) whose separation is inside the horizon,
// with the sphere |ξ| = δ replaced by a plane normal to e = ξ/|ξ|, moved in by
// the mean curvature offset τ of the lateral spread (|ξ'| ≈ r + Z + |t|²/(2r)):
//
//   Z = e·(v_h − v_g), v uniform in the boxes;  d = δ − r − τ;  φ = P(Z < d),
//   r_eff = r + E[Z | Z < d]   (the mean separation of the inside part along e).
//
// The bond then acts with W φ c(r_eff) (r_eff / r)² e eᵀ: its energy under a
// uniform strain, ½ W φ c(r_eff) r_eff² (e·ε·e)², is the box-pair integral of
// the continuum energy density to second order. Bonds with d ≥ reach are
// untouched (φ = 1, r_eff = r) and bonds with d ≤ −reach are absent, where
// reach = Σ_i |e_i| (b_gi + b_hi) (τ ≥ 0, so r − reach ≥ δ is absent too).

#include "perimorph/core/types.hpp"

#include <array>
#include <cmath>

namespace perimorph::peridynamics {

/// Fraction φ of a bond inside the horizon and the effective length r_eff.
struct EdgeWeight {
  double fraction = 1.0;
  double r_eff = 0.0;
};

/// Largest separation beyond r at which a box pair can still reach into the
/// horizon: Σ_i |e_i| (b_gi + b_hi) with e = ξ / r.
template <int D>
double edge_reach(const Vec3& xi, double r, const Vec3& half_g, const Vec3& half_h) {
  double reach = 0.0;
  for (int i = 0; i < D; ++i) reach += std::abs(xi[i]) / r * (half_g[i] + half_h[i]);
  return reach;
}

/// φ and r_eff for the bond ξ = x_h − x_g (|ξ| = r > 0), horizon δ, boxes of
/// half-widths half_g, half_h (THEORY §4, partial-volume option; see the file
/// comment). Pure: no allocation.
template <int D>
EdgeWeight edge_weight(const Vec3& xi, double r, const Vec3& half_g, const Vec3& half_h, double delta) {
  const double reach = edge_reach<D>(xi, r, half_g, half_h);
  if (r + reach <= delta) return {1.0, r};
  // Curvature: a lateral offset t moves the separation out by |t|²/(2r); its
  // mean τ = Σ_i (1 − e_i²) (b_gi² + b_hi²)/3 / (2r) shifts the plane inwards.
  double tau = 0.0;
  for (int i = 0; i < D; ++i) {
    const double e = xi[i] / r;
    tau += (1.0 - e * e) * (half_g[i] * half_g[i] + half_h[i] * half_h[i]) / 3.0;
  }
  tau /= 2.0 * r;
  const double d = delta - r - tau;
  if (d >= reach) return {1.0, r};
  if (d <= -reach) return {0.0, r};
  // Z = Σ_j U_j, U_j uniform on [−c_j/2, c_j/2]; widths below 1e-4 of the
  // largest are dropped (their effect is second order in the width, and the
  // alternating sum below loses digits as Π c_j → 0).
  std::array<double, 2 * D> c{};
  int k = 0;
  double cmax = 0.0;
  for (int i = 0; i < D; ++i) cmax = std::max(cmax, std::abs(xi[i]) / r * std::max(half_g[i], half_h[i]));
  for (int i = 0; i < D; ++i)
    for (const double b : {half_g[i], half_h[i]}) {
      const double w = 2.0 * std::abs(xi[i]) / r * b;
      if (w > 2e-4 * cmax) c[static_cast<std::size_t>(k++)] = w;
    }
  double total = 0.0, prod = 1.0, fact = 1.0;
  for (int j = 0; j < k; ++j) {
    total += c[static_cast<std::size_t>(j)];
    prod *= c[static_cast<std::size_t>(j)];
    fact *= j + 1;
  }
  // S = Σ V_j with V_j uniform on [0, c_j]: Z < d ⇔ S < t = d + total/2.
  // F(t) = Σ_{subsets A} (−1)^|A| (t − c_A)₊^k / (k! Π c),
  // ∫₀^t F = Σ_A (−1)^|A| (t − c_A)₊^(k+1) / ((k+1)! Π c).
  const double t = d + 0.5 * total;
  double F = 0.0, G = 0.0;
  for (int mask = 0; mask < (1 << k); ++mask) {
    double shift = 0.0;
    int bits = 0;
    for (int j = 0; j < k; ++j)
      if (mask & (1 << j)) {
        shift += c[static_cast<std::size_t>(j)];
        ++bits;
      }
    const double u = t - shift;
    if (u <= 0.0) continue;
    const double sign = bits % 2 ? -1.0 : 1.0;
    const double uk = std::pow(u, k);
    F += sign * uk;
    G += sign * uk * u;
  }
  F /= fact * prod;
  G /= fact * (k + 1) * prod;
  if (F <= 0.0) return {0.0, r};
  if (F >= 1.0) F = 1.0;
  // E[S | S < t] = t − G/F, so r_eff = r + E[Z | Z < d] = r + d − G/F (the
  // kernel is read at the inside part's mean along e; continuous with r_eff = r
  // at d = reach, where F = 1 and E[Z] = 0).
  return {F, r + d - G / F};
}

}  // namespace perimorph::peridynamics
